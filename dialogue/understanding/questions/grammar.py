"""Questions about the situation ("what do you see", "where is X"...), on whole words.

A where-question is said many ways ("where did we put X", "where'd I leave my X", "where would I
find X", "has anyone seen X", "(do you happen to know) where X went", "which room is X in"), a
who-question about a place too ("who's waiting at reception", "tell me the name of the person in
the break room").

The result is a `Parse` with `act="question"`, a question kind and the phrase it is about; the
answer is computed from the KB snapshot in dialogue.understanding.questions.answers.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Literal

from dialogue.reference.english import Words
from dialogue.understanding.language import Language
from dialogue.understanding.parsed import Parse
from dialogue.understanding.questions.presence import presence
from dialogue.understanding.questions.recalled import recalled
from dialogue.understanding.questions.vocabulary import QuestionWords
from dialogue.understanding.speech.plain import split_at, starts


def _q(kind: str, w: Words, **slots: Words) -> Parse:
    return Parse("question", question=kind, slots=dict(slots), words=w)


def _strip_ends(thing: Words, lead: frozenset[str], tail: frozenset[str]) -> Words:
    while thing[:1] and thing[0] in lead:
        thing = thing[1:]
    while thing[-1:] and thing[-1] in tail:
        thing = thing[:-1]
    return thing


def question(lang: Language, words: list[str]) -> Parse | None:
    """The question the words ask, read by the first of `_STEPS` that takes them; None when they
    ask none."""
    q = lang.derived(QuestionWords)
    w = tuple(words)
    if _telling(q, w) and w[2] == "about":
        return _q("what_is", w, thing=w[3:])
    w = _indirect(q, _told(q, w))
    asked = recalled(lang, w)  # "what did I ask you for?", "what's left?"
    if asked is not None:
        return asked
    w = _described(q, w)  # "describe the objects on the bench": what is on it
    w = _count_said(q, w)  # "count the canoes in the shed": how many
    for step in _STEPS:
        found = step(q, w)
        if found is not None:
            return None if found is False else found
    return None


#: What a step makes of the words: the question, None when they are not its kind of question (the
#: next step reads them), False when they are no question at all ("is there anything to eat").
_Read = Parse | Literal[False] | None


def _telling(q: QuestionWords, w: Words) -> bool:
    """Whether the words ask to be told or shown a wh-question ("tell me where...", "show me
    what..."; "show me where the lounge is" is guiding)."""
    shown = bool(q.show_me) and w[:2] == q.show_me and w[2:3] != ("where",)
    return bool((q.tell_me and w[:2] == q.tell_me) or shown) and len(w) > 2 and w[2] in q.wh | {"about"}


def _told(q: QuestionWords, w: Words) -> Words:
    """ "tell me where the keys are": the question itself."""
    return w[2:] if _telling(q, w) else w


def _indirect(q: QuestionWords, w: Words) -> Words:
    """ "do you know where the keys are": the question itself."""
    for lead in q.indirect.of(w):
        if w[len(lead) : len(lead) + 1] and w[len(lead)] in q.wh:
            return w[len(lead) :]
    return w


def _seen_by_anyone(q: QuestionWords, w: Words) -> _Read:
    """ "has anyone seen my keys": where they are."""
    for lead in q.seen_by_anyone.of(w):
        if _strip_ends(w[len(lead) :], frozenset(), q.nearby):
            return _q("where", w, thing=_strip_ends(w[len(lead) :], frozenset(), q.nearby))
    return None


def _anybody_here(q: QuestionWords, w: Words) -> _Read:
    """ "is anybody else here", "is there anyone around"."""
    return _q("who_see", w) if _anybody(q, w) else None


def _whose(q: QuestionWords, w: Words) -> _Read:
    head = w[:1]
    belongs = bool(q.belong_to) and w[-2:] == q.belong_to
    if head == ("whose",) or (head == ("who",) and (belongs or w[1:2] == ("owns",))):
        return _q("whose", w, thing=_owned_thing(q, w))
    return None


def _what_heads(q: QuestionWords, w: Words) -> _Read:
    return _what(q, w) if w[:1] and w[0] in q.what_heads else None


def _who(q: QuestionWords, w: Words) -> _Read:
    if w[:1] != ("who",):
        return None
    if "you" in w and "are" in w and "see" not in w:
        return _q("name", w)
    if w[1:2] == ("is",) and w[2:] and w[2] not in q.who_not_a_name and not _who_at(q, w[1:]):
        return _q("what_is", w, thing=w[2:])
    at = _who_at(q, w[1:])  # "who's at the box office", "who is waiting at reception"
    if at:
        return _q("who_in", w, place=at)
    # ("who else is down the allotment today": words besides the seeing question's, for the KB to know)
    rest = tuple(x for x in w[1:] if x not in q.who_sees)
    return _q("who_see", w, rest=rest) if rest else _q("who_see", w)


def _where_head(q: QuestionWords, w: Words) -> _Read:
    return _where(q, w) if w[:1] == ("where",) else None


def _how_many(q: QuestionWords, w: Words) -> _Read:
    if q.how_many and starts(w, q.how_many):
        return _q("how_many", w, thing=_counted(q, w[2:]))
    return None


def _seen(q: QuestionWords, w: Words) -> _Read:
    """ "do you see the cup", "is there any fruit around", "is there anything on the table"."""
    seeing = q.sees.first(w)
    # ("do you have to go": a duty, nothing seen)
    if seeing is None or (w[len(seeing) : len(seeing) + 1] and w[len(seeing)] in q.not_seen_before):
        return None
    thing = _strip_ends(w[len(seeing) :], frozenset(), q.nearby)  # "is there any fruit around"
    if thing[:1] and thing[0] in q.anything:
        if q.purpose(thing[1:3]) is not None and not thing[3:] and seeing in q.available:
            return False  # "is there anything to eat": a need (requests/needs), no question
        return _anything(q, w, thing[1:])
    return _q("can_see", w, thing=thing)


def _came(q: QuestionWords, w: Words) -> _Read:
    """ "has Frances arrived?", "did Tom leave?"."""
    return presence(q.lang, w)


def _here(q: QuestionWords, w: Words) -> _Read:
    """ "is Maria here?", "is Yuki here yet?", "is Blessing still here?"."""
    here = (*w[:2], *(x for x in w[2:] if x not in q.there_after)) if len(w) > 3 else w
    if w[:1] and w[0] in q.is_are and len(here) > 2 and here[-1] in q.there:
        return _q("can_see", w, thing=here[1:-1])
    return None


def _still_on(q: QuestionWords, w: Words) -> _Read:
    """ "is the cup (still) on the table?"."""
    if w[:1] and w[0] in q.is_are and split_at(w, q.locatives) is not None:
        return _q("can_see", w, thing=tuple(x for x in w[1:] if x not in q.there_after))
    return None


def _how(q: QuestionWords, w: Words) -> _Read:
    if w[:1] != ("how",):
        return None
    return _q("how_are_you" if q.social_how.of(w) else "other", w)


def _other(q: QuestionWords, w: Words) -> _Read:
    return _q("other", w) if w[:1] and w[0] in q.wh else None


def _described(q: QuestionWords, w: Words) -> Words:
    """The question "describe the objects on the bench" or "list the people in the foyer" asks, in
    its own words ("what is on the bench", "who is in the foyer"), when the words after what is
    described say where; else the words unchanged."""
    lead = q.describe.first(w)
    if lead is None:
        return w
    rest = w[len(lead) :]
    rest = rest[1:] if rest[:1] and rest[0] in q.determiners else rest
    asked = q.described.get(rest[0]) if rest else None
    return (*asked, *rest[1:]) if asked and split_at(rest, q.locatives) is not None else w


def _count_said(q: QuestionWords, w: Words) -> Words:
    """The question "count the canoes you can see" or "count how many cups there are" asks, in its
    own words ("how many the canoes you can see"), when a determiner or "how many" follows the
    lead; else the words unchanged ("count to ten", "count me in")."""
    lead = q.count.first(w)
    if lead is None:
        return w
    rest = w[len(lead) :]
    if starts(rest, q.how_many):
        return rest
    return (*q.how_many, *rest) if rest[:1] and rest[0] in q.determiners else w


def _unposed(q: QuestionWords, words: Words) -> Words:
    """The words without a verb of how a thing is placed right before where it is ("the phone
    (lying) on the counter")."""
    before_place = [i + 1 < len(words) and words[i + 1] in q.place_starts for i in range(len(words))]
    return tuple(x for x, placed in zip(words, before_place, strict=True) if x not in q.posture or not placed)


def _who_at(q: QuestionWords, rest: Words) -> Words:
    """The place of "who is at X", "who is on the shop floor", "who's waiting at reception", "who's
    getting ready in X" (a verb of being somewhere between, with a word of its own), else ()."""
    if not rest[:1] or rest[0] not in q.be:
        return ()
    at = 1
    if rest[1:2] and rest[1] in q.who_pointing:  # "who's that at the long table": who is there
        at = 2
    elif rest[1:2] and rest[1].endswith("ing") and rest[1] not in q.who_at:
        at = 3 if rest[2:3] and rest[2] not in q.who_at else 2
    return rest[at + 1 :] if rest[at : at + 1] and rest[at] in q.who_at and len(rest) > at + 1 else ()


def _name_of(q: QuestionWords, w: Words) -> Parse | None:
    """ "tell me the name of the person in the break room", "what's the name of the man at
    reception": who is there."""
    if (q.tell_me and starts(w, q.tell_me)) or (w[:1] == ("what",) and w[1:2] and w[1] in q.be):
        rest = w[2:]
    else:
        return None
    lead = q.name_of.first(rest)
    if lead is None:
        return None
    who = rest[len(lead) :]
    who = who[1:] if who[:1] == ("the",) else who
    if len(who) < 3 or who[0] not in q.whoever or who[1] not in q.who_at:
        return None
    return _q("who_in", w, place=who[2:])


def _counted(q: QuestionWords, rest: Words) -> Words:
    """What "how many" counts: the words before the question's own clause ("watering cans (have we
    got)", "cups (can you see)", "chairs (are there) in the hall")."""
    at = next((i for i in range(1, len(rest) - 1)
               if rest[i] in q.asking_verbs and rest[i + 1] in q.asked_subjects), None)  # fmt: skip
    if at is None:
        return tuple(x for x in rest if x not in q.count_glue)
    after = rest[at + 2 :]
    while after[:1] and after[0] in q.count_after:
        after = after[1:]
    thing = rest[:at] + (after if after[:1] and after[0] in q.place_starts else ())
    return _strip_ends(thing, frozenset(), q.count_tail)


def _anybody(q: QuestionWords, w: Words) -> bool:
    if not w[:1] or w[0] not in q.is_are:
        return False
    rest = w[2:] if w[1:2] == ("there",) else w[1:]
    return bool(rest) and rest[0] in q.someone and not set(rest[1:]) - q.who_not_a_name - q.else_


def _what(q: QuestionWords, w: Words) -> Parse:
    rest = w[1:]
    if w[0] == "which" and len(rest) > 3 and rest[0] in q.rooms and rest[1] in q.be and rest[-1] == "in":
        return _q("where", w, thing=rest[2:-1])  # "which room is the novel in"
    if len(rest) > 2 and rest[-2] in q.be and (rest[-1] in q.owners or rest[-1].endswith("'s")):
        return _q("whose", w, thing=rest[:-2])  # "which suitcase is mine": whose each one is
    if w[0] == "which" and 1 < len(rest) < 5 and rest[-2] in q.be and rest[-1] in q.colours:
        return _q("which_see", w, thing=(rest[-1], *rest[:-2]))  # "which marker is red"
    if _before_you(q, rest) or "around" in rest:  # "what's in front of you" ("the front bench" is a name)
        return _q("what_see", w)
    if rest[:1] and rest[0] in q.colour_words:
        return _q(
            "colour", w, thing=_strip_ends(rest[1:], q.is_are, q.is_are)
        )
    for near in q.near:  # "what's next to the window": what the KB puts there
        found = split_at(("x", *rest), [near])
        if found and found[2] and not set(found[0][1:]) - q.on_glue:
            return _q("what_near", w, place=found[2], relation=near)
    placed = _what_placed(q, w, rest)
    if placed is not None:
        return placed
    for i, word in enumerate(rest):  # "which cups do you see", "what fruit can you see"
        seeing = word in q.seeing_aux and rest[i + 1 : i + 3] == q.you_see
        if seeing and i > 0 and not set(rest[:i]) & q.not_which_see:
            return _q("which_see", w, thing=rest[:i])
    if set(rest) & q.see_words and "name" not in rest:
        return _q("what_see", w)
    if rest[:1] and rest[0] in q.is_are and set(rest) & q.name_words and not _someone_elses(q, rest):
        return _q("name", w)
    if (
        rest[:1]
        and rest[0] in q.is_are
        and len(rest) > 1
        and not set(rest) & q.not_what_is
    ):
        return _q("what_is", w, thing=rest[1:])
    return _q("other", w)


def _what_placed(q: QuestionWords, w: Words, rest: Words) -> Parse | None:
    """ "what is on the table": what the KB puts there; "which oars are on the rack", "what fruit is
    lying on the table": those of the kind there."""
    for sep in q.locatives:
        found = split_at(("x", *rest), [sep])
        if found is None:
            continue
        if not set(found[0][1:]) - q.on_glue:
            return _q("what_on", w, place=found[2], relation=(" ".join(sep),))
        kind = _kind_placed(q, found[0][1:]) if found[2] else ()
        if kind:
            return _q("which_on", w, thing=kind, place=found[2], relation=(" ".join(sep),))
    return None


def _kind_placed(q: QuestionWords, before: Words) -> Words:
    """The kind of "(which) oars are (lying)" before a place: the words before the verb of being,
    when they are only that and none of them says how or what is seen; else ()."""
    before = before[:-1] if before[-1:] and before[-1] in q.posture else before
    if len(before) < 2 or before[-1] not in q.is_are or set(before[:-1]) & (q.on_glue | q.be):
        return ()
    return before[:-1]


def _before_you(q: QuestionWords, rest: Words) -> bool:
    """Whether the words ask what is in front of the robot ("in front", "in front of you")."""
    at = next((i for i in range(len(rest) - 1) if rest[i : i + 2] == q.in_front), None)
    return at is not None and (not rest[at + 2 :] or rest[at + 2 :] in q.front_of)


def _someone_elses(q: QuestionWords, rest: Words) -> bool:
    """ "what is her name", "what is the name of Alice": a name, but not the robot's."""
    return bool(set(rest) & q.others) or any(x.endswith("'s") for x in rest) or "of" in rest


def _anything(q: QuestionWords, w: Words, rest: Words) -> Parse:
    """ "is there anything on the table", "do you see anything to eat", "can you see anything"."""
    wanted = q.purpose(rest[:2])
    if wanted is not None:
        return _q("can_see", w, thing=(*wanted, *rest[2:]))
    found = split_at(("x", *rest), q.locatives)
    if found is not None and found[0] == ("x",):
        return _q("what_on", w, place=found[2])
    return _q("what_see", w)


def _owned_thing(q: QuestionWords, w: Words) -> Words:
    """The thing of "whose phone is this", "whose is the mug", "who does the cup belong to", "who owns it"."""
    rest = w[1:]
    if rest[:1] and rest[0] in q.does and q.belong_to and rest[-2:] == q.belong_to:
        return rest[1:-2]
    if rest[:1] == ("owns",):
        return rest[1:]
    if rest[:1] and rest[0] in q.be:  # "whose is the mug"
        return rest[1:]
    # "whose phone is on the bookcase": the verb drops out, the place stays a qualifier.
    thing = _unposed(q, tuple(x for x in rest if x not in q.be))
    return thing if [x for x in thing if x not in q.demonstratives] else ("it",)


def _where(q: QuestionWords, w: Words) -> Parse:
    rest = w[1:]
    while len(rest) > 3 and rest[-1] in q.where_tail and rest[-3:-1] in q.got_to:
        rest = rest[:-1]  # ("where's the remote got to now")
    if rest[-2:] in q.got_to:  # "where's my cup got to"
        rest = rest[:-2]
        if rest[:1] and rest[0] in q.did:
            rest = ("is", *rest[1:])
    # "where did Uma go?", "where's my jacket gone" ("is" for "has", as said)
    gone = rest[-1:] == ("gone",) and rest[:1] and rest[0] in q.is_are
    went = rest[-1:] and rest[-1] in q.went and rest[:1] and rest[0] in q.did
    if gone or went:
        return _q("where", w, thing=rest[1:-1])
    if len(rest) > 1 and rest[-1] in q.gone and rest[0] not in q.asker:
        return _q("where", w, thing=rest[:-1])  # "(do you happen to know) where the stapler went"
    placed = _placed_thing(q, rest)
    if placed:  # "where did we put the tape", "where would I find a pear", "where Dana left her phone"
        return _q("where", w, thing=placed)
    if len(rest) > 1 and rest[-1] in q.be and rest[0] not in q.be:
        return _q("where", w, thing=rest[:-1])  # the indirect order: "(do you know) where the keys are"
    if rest in q.where_am_i:
        return _q("where", w, thing=("me",))
    if q.are_you and rest == q.are_you:
        return _q("where", w, thing=("you",))
    for lead in q.where_leads:
        if starts(rest, lead):
            thing = _strip_ends(rest[len(lead) :], frozenset(), q.where_tail)
            if thing:
                return _q("where", w, thing=thing)
    return _q("other", w)


def _placed_thing(q: QuestionWords, rest: Words) -> Words:
    """The thing of "where did we put X", "where would I find X", "where Dana left her X": the
    words after a verb of putting or finding, when only an auxiliary and who did it (a pronoun, or
    one word: a name) come before it; () otherwise."""
    at = next((i for i, x in enumerate(rest[:4]) if x in q.placing), None)
    if at is None or not rest[at + 1 :]:
        return ()
    before = [x for x in rest[:at] if x not in q.asker]
    if len(before) > 1 or (before and rest[:1] and rest[0] in q.be):
        return ()
    return _strip_ends(rest[at + 1 :], frozenset(), q.nearby | q.where_tail)


#: The kinds of question, in the order they are tried.
_STEPS: tuple[Callable[[QuestionWords, Words], _Read], ...] = (
    _name_of, _seen_by_anyone, _anybody_here, _whose, _what_heads, _who, _where_head, _how_many,
    _seen, _came, _here, _still_on, _how, _other,
)  # fmt: skip
