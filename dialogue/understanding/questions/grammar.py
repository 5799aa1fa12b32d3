"""Questions about the situation ("what do you see", "where is X"...), on whole words.

The result is a `Parse` with `act="question"`, a question kind and the phrase it is about; the
answer is computed from the KB snapshot in dialogue.understanding.questions.answers.
"""

from __future__ import annotations

from dialogue.reference.english import COLOURS, Words, word_set
from dialogue.understanding.language import Language
from dialogue.understanding.parsed import Parse
from dialogue.understanding.speech.plain import split_at, starts

_SEES: tuple[Words, ...] = tuple(
    tuple(p.split()) for p in ("do you see", "can you see", "could you see", "have you seen", "did you see",
                               "are you seeing", "do you have", "is there", "are there")
)  # fmt: skip
_WHERE_LEADS: tuple[Words, ...] = tuple(
    tuple(p.split()) for p in ("is", "are", "can i find", "did you see", "did i put", "do you see", "was",
                               "were", "have you seen", "did i leave", "should i look for", "i put", "i left")
)  # fmt: skip
_ON_GLUE = word_set(
    "is are do you see can lying there objects things thing stuff placed sitting kept have has we got"
)
_WHO_NOT_A_NAME = word_set("here there around in with present speaking talking at near next else home")
_SEE_WORDS = frozenset({"see", "notice", "around", "front", "here", "there"})
_COLOUR_WORDS = frozenset({"colour", "color"})
_LOCATIVES = ("on top of", "on", "in", "inside", "under", "at")
#: Relations beside support and zone a "what is ... X" question may ask about.
_NEAR = ("next to", "close to", "in front of", "near", "beside", "by", "behind", "underneath", "below",
         "beneath", "above")
#: Leads of an indirect question: "do you know where the keys are", "any idea where the toolbox is".
_INDIRECT: tuple[Words, ...] = tuple(
    tuple(p.split()) for p in ("do you know", "do you have any idea", "any idea", "have you any idea",
                               "can you tell me", "could you tell me", "i wonder", "i am wondering",
                               "i was wondering", "find out", "check", "go and see", "see")
)  # fmt: skip
_BE = frozenset({"is", "are", "was", "were"})
_SOMEONE = word_set("anybody anyone somebody someone people")
_ELSE = word_set("else besides except apart from but me us other than the room this")
_OWNERS = word_set("mine yours his hers theirs ours")
_NEARBY = word_set("around nearby here about anywhere somewhere")
_OTHERS = word_set("his her their my its")
#: Words that ask whether someone is there ("is Maria about?").
_THERE = word_set("here there around present about")


def _q(kind: str, w: Words, **slots: Words) -> Parse:
    return Parse("question", question=kind, slots=dict(slots), words=w)


def _strip_ends(thing: Words, lead: frozenset[str], tail: frozenset[str]) -> Words:
    while thing[:1] and thing[0] in lead:
        thing = thing[1:]
    while thing[-1:] and thing[-1] in tail:
        thing = thing[:-1]
    return thing


def question(lang: Language, words: list[str]) -> Parse | None:  # noqa: C901
    wh = lang.words.wh
    w = tuple(words)
    if w[:2] in {("tell", "me"), ("show", "me")} and len(w) > 2 and w[2] in wh | {"about"}:
        if w[2] == "about":
            return _q("what_is", w, thing=w[3:])
        w = w[2:]
    for lead in _INDIRECT:
        if starts(w, lead) and w[len(lead) : len(lead) + 1] and w[len(lead)] in wh:
            w = w[len(lead) :]
            break
    head = w[:1]
    if _anybody(w):  # "is anybody else here", "is there anyone around"
        return _q("who_see", w)
    if head == ("whose",) or (head == ("who",) and (w[-2:] == ("belong", "to") or w[1:2] == ("owns",))):
        return _q("whose", w, thing=_owned_thing(w))
    if head in {("what",), ("which",)}:
        return _what(w)
    if head == ("who",):
        if "you" in w and "are" in w and "see" not in w:
            return _q("name", w)
        if w[1:2] == ("is",) and w[2:] and w[2] not in _WHO_NOT_A_NAME:
            return _q("what_is", w, thing=w[2:])
        at = w[2:3] in {("at",), ("in",), ("inside",)} and w[1:2] in {("is",), ("are",)} and len(w) > 3
        return _q("who_in", w, place=w[3:]) if at else _q("who_see", w)  # "who's at the box office"
    if head == ("where",):
        return _where(w)
    if starts(w, ("how", "many")):
        return _q("how_many", w, thing=_counted(w[2:]))
    for lead in _SEES:
        if starts(w, lead):
            thing = _strip_ends(w[len(lead) :], frozenset(), _NEARBY)  # "is there any fruit around"
            if thing[:1] in {("anything",), ("something",)}:
                return _anything(lang, w, thing[1:])
            return _q("can_see", w, thing=thing)
    if head in {("is",), ("are",)} and len(w) > 2 and w[-1] in _THERE:
        return _q("can_see", w, thing=w[1:-1])  # "is Maria here?"
    if head in {("is",), ("are",)} and split_at(w, _LOCATIVES) is not None:
        return _q("can_see", w, thing=w[1:])  # "is the cup on the table?"
    if head == ("how",):
        social = starts(w, ("how", "are", "you")) or starts(w, ("how", "is", "it", "going"))
        return _q("how_are_you" if social else "other", w)
    if head and head[0] in wh:
        return _q("other", w)
    return None


#: The verb of a question's own clause after what it counts ("how many cans *have* we got").
_ASKING_VERBS = word_set("do does did have has can could are is were was will would")
_ASKED_SUBJECTS = word_set("we you i they there")
#: Words after a counted thing that only say where or in all ("here", "left", "altogether").
_COUNT_TAIL = word_set("here there around left altogether total in all now got")


def _counted(rest: Words) -> Words:
    """What "how many" counts: the words before the question's own clause ("watering cans (have we
    got)", "cups (can you see)", "chairs (are there) in the hall")."""
    at = next((i for i in range(1, len(rest) - 1)
               if rest[i] in _ASKING_VERBS and rest[i + 1] in _ASKED_SUBJECTS), None)  # fmt: skip
    if at is None:
        return tuple(x for x in rest if x not in {"do", "you", "see", "can", "are", "there", "is"})
    after = rest[at + 2 :]
    while after[:1] and after[0] in {"got", "see", "have", "left", "here", "around"}:
        after = after[1:]
    thing = rest[:at] + (after if after[:1] and after[0] in _PLACE_STARTS else ())
    return _strip_ends(thing, frozenset(), _COUNT_TAIL)


_PLACE_STARTS = word_set("in on at under inside")


def _anybody(w: Words) -> bool:
    if not w[:1] or w[0] not in {"is", "are"}:
        return False
    rest = w[2:] if w[1:2] == ("there",) else w[1:]
    return bool(rest) and rest[0] in _SOMEONE and not set(rest[1:]) - _WHO_NOT_A_NAME - _ELSE


def _what(w: Words) -> Parse:
    rest = w[1:]
    if len(rest) > 2 and rest[-2] in _BE and (rest[-1] in _OWNERS or rest[-1].endswith("'s")):
        return _q("whose", w, thing=rest[:-2])  # "which suitcase is mine": whose each one is
    if w[0] == "which" and 1 < len(rest) < 5 and rest[-2] in _BE and rest[-1] in COLOURS:
        return _q("which_see", w, thing=(rest[-1], *rest[:-2]))  # "which marker is red"
    if _before_you(rest) or "around" in rest:  # "what's in front of you" ("the front bench" is a name)
        return _q("what_see", w)
    if rest[:1] and rest[0] in _COLOUR_WORDS:
        return _q(
            "colour", w, thing=_strip_ends(rest[1:], frozenset({"is", "are"}), frozenset({"is", "are"}))
        )
    for sep in _NEAR:  # "what's next to the window": what the KB puts there
        found = split_at(("x", *rest), [sep])
        if found and found[2] and not set(found[0][1:]) - _ON_GLUE:
            return _q("what_near", w, place=found[2], relation=tuple(sep.split()))
    for sep in _LOCATIVES:
        found = split_at(("x", *rest), [sep])
        if found and not set(found[0][1:]) - _ON_GLUE:
            return _q("what_on", w, place=found[2], relation=(sep,))
    for i, word in enumerate(rest):  # "which cups do you see", "what fruit can you see"
        seeing = word in {"do", "can", "could"} and rest[i + 1 : i + 3] == ("you", "see")
        if seeing and i > 0 and not set(rest[:i]) & {"is", "are", "else"}:
            return _q("which_see", w, thing=rest[:i])
    if set(rest) & _SEE_WORDS and "name" not in rest:
        return _q("what_see", w)
    if rest[:1] in {("is",), ("are",)} and set(rest) & {"name", "called"} and not _someone_elses(rest):
        return _q("name", w)
    if (
        rest[:1] in {("is",), ("are",)}
        and len(rest) > 1
        and not set(rest) & {"you", "your", "time", "weather"}
    ):
        return _q("what_is", w, thing=rest[1:])
    return _q("other", w)


def _before_you(rest: Words) -> bool:
    """Whether the words ask what is in front of the robot ("in front", "in front of you")."""
    at = next((i for i in range(len(rest) - 1) if rest[i : i + 2] == ("in", "front")), None)
    return at is not None and rest[at + 2 :] in {(), ("of", "you"), ("of", "me"), ("of", "us")}


def _someone_elses(rest: Words) -> bool:
    """ "what is her name", "what is the name of Alice": a name, but not the robot's."""
    return bool(set(rest) & _OTHERS) or any(x.endswith("'s") for x in rest) or "of" in rest


def _anything(lang: Language, w: Words, rest: Words) -> Parse:
    """ "is there anything on the table", "do you see anything to eat", "can you see anything"."""
    wanted = lang.requests.purpose(rest[:2])
    if wanted is not None:
        return _q("can_see", w, thing=(*wanted, *rest[2:]))
    found = split_at(("x", *rest), _LOCATIVES)
    if found is not None and found[0] == ("x",):
        return _q("what_on", w, place=found[2])
    return _q("what_see", w)


def _owned_thing(w: Words) -> Words:
    """The thing of "whose phone is this", "whose is the mug", "who does the cup belong to", "who owns it"."""
    rest = w[1:]
    if rest[:1] in {("does",), ("do",)} and rest[-2:] == ("belong", "to"):
        return rest[1:-2]
    if rest[:1] == ("owns",):
        return rest[1:]
    if rest[:1] and rest[0] in _BE:  # "whose is the mug"
        return rest[1:]
    # "whose phone is on the bookcase": the verb drops out, the place stays a qualifier.
    thing = tuple(x for x in rest if x not in _BE)
    return thing if [x for x in thing if x not in {"this", "that", "these", "those"}] else ("it",)


def _where(w: Words) -> Parse:
    rest = w[1:]
    if rest[-2:] in {("got", "to"), ("get", "to"), ("gone", "to")}:  # "where's my cup got to"
        rest = rest[:-2]
        if rest[:1] in {("did",), ("has",), ("have",)}:
            rest = ("is", *rest[1:])
    # "where did Uma go?", "where's my jacket gone" ("is" for "has", as said)
    gone = rest[-1:] == ("gone",) and rest[:1] in {("is",), ("are",)}
    went = rest[-1:] and rest[-1] in {"go", "gone", "went"} and rest[:1] and rest[0] in {"did", "has", "have"}
    if gone or went:
        return _q("where", w, thing=rest[1:-1])
    if len(rest) > 1 and rest[-1] in _BE and rest[0] not in _BE:
        return _q("where", w, thing=rest[:-1])  # the indirect order: "(do you know) where the keys are"
    if rest in {("am", "i"), ("are", "we")}:
        return _q("where", w, thing=("me",))
    if rest == ("are", "you"):
        return _q("where", w, thing=("you",))
    for lead in _WHERE_LEADS:
        if starts(rest, lead):
            thing = _strip_ends(
                rest[len(lead) :], frozenset(), frozenset({"located", "now", "placed", "kept"})
            )
            if thing:
                return _q("where", w, thing=thing)
    return _q("other", w)
