"""Answers to the robot's last question: a fragment that completes the pending request ("the red
one", "mine, obviously", "the pink one, it's Carla's"), a yes or a no to "Do you mean the flat
brush?", a yes to an offer ("Would you like me to bring you a basket?" "yes please") and "both" to
"Which mug do you mean...?"; a correction of the request just made ("sorry, I meant screen two", "no,
the blue one"); and the same request for another
thing ("and the soup goes to table two" after "take the steak to table four").

The robot's question must be the latest utterance (system notes aside); a fragment or a confirmation
re-reads the request said right before it, an accepted offer is read as the request the robot made.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

from dialogue import intents as I
from dialogue.history import Utterance
from dialogue.prompts import FREE_FORM_OBJECT
from dialogue.reference.english import Words, tokens
from dialogue.reference.grounding import Kind
from dialogue.reference.resolution import ROLE_KINDS, content_words, resolve
from dialogue.understanding.context import Reader
from dialogue.understanding.followups import proposal
from dialogue.understanding.followups.accepting import accepts
from dialogue.understanding.language import Language
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.parsed import Parse
from dialogue.understanding.replies import say, then
from dialogue.understanding.requests.commands import parse
from dialogue.understanding.requests.constructions import where_it_goes
from dialogue.understanding.said import Said
from dialogue.understanding.speech.clauses import clauses, described, description
from dialogue.understanding.speech.plain import expanded, plain, strip_politeness


def follow_up(reader: Reader, p: Parse, heard: Said) -> Outcome | None:
    """What the words answer of the robot's last question, or None when they answer none."""
    spoken = [i for i, u in enumerate(reader.history) if u.role != "system"]
    if not spoken:
        return None
    question = reader.history[spoken[-1]]
    if question.role != "assistant" or not question.text.rstrip().endswith("?"):
        return None
    lang = reader.lexicon.lang
    answer = [lang.followups.no.get(w, w) for w in expanded(lang, heard)]
    said = [w for w in answer if w != "no"]
    confirmed = proposal.answered(reader, answer)
    if confirmed is not None:  # "yes" or "no" to "Shall I bring the soap to Jordan?"
        return confirmed
    accepted = offer(reader, question, said)
    if accepted is not None:
        return accepted
    found = _pending(reader, spoken, heard)
    if found is None:
        return None
    before, pending = found
    earlier = reader.within(reader.history[:before])
    first = earlier.act(pending)
    if first.open_role is None:
        return None
    confirmed = confirmation(earlier, pending, first, question, answer)
    if confirmed is not None:
        return _sure(confirmed)
    if tuple(said) in lang.followups.both:
        return _every(earlier, pending, first)
    fragment, more = _fragment(lang, p, heard)
    if not fragment:
        return None
    merged = _merged(lang, fragment, first)
    if more is not None:  # "the pink one, it's Carla's"
        merged = described(lang, merged, more)
    role = first.open_role
    if role == "object" and pending.intent in FREE_FORM_OBJECT:  # "What should I say?" "Dinner is ready"
        pending = replace(pending, text=heard.text.strip().rstrip(".!?").strip() or None)
    outcome = earlier.act(pending, {role: merged})
    if outcome.intent is None and not outcome.clarify:
        return None
    unknown = [w for w in content_words(lang, fragment) if w in lang.words.positions]
    if outcome.clarify and unknown:  # "the left one": the KB says nothing of left and right
        note = say(lang, "request.position_unknown", position=unknown[0])
        return replace(_sure(outcome), reply=f"{note} {outcome.reply}")
    return _sure(outcome)


def _every(earlier: Reader, pending: Parse, first: Outcome) -> Outcome | None:
    """ "both" to "Which mug do you mean: the blue one or the red one?": the request for each thing
    the question told apart, in turn (None: it asked about no such things)."""
    role = first.open_role
    kinds = ROLE_KINDS.get(pending.intent or "", {}).get(role or "")
    if role is None or kinds is None or not first.open_phrase:
        return None
    each = [earlier.act(pending, {role: tuple(tokens(e.id))})
            for e in resolve(earlier.lexicon, first.open_phrase, kinds).matches]
    if len(each) < 2 or any(o.intent is None for o in each):
        return None
    said = then(earlier.lexicon.lang, [o.reply for o in each])
    return replace(_sure(each[0]), reply=said, more=tuple(_sure(o) for o in each[1:]))


#: How many answers the same question may have had before this one ("the left one", asked again).
_ASKED_AGAIN = 2


def _pending(reader: Reader, spoken: list[int], heard: Said) -> tuple[int, Parse] | None:
    """The request the robot's question is about, and where it was said: the person's words before
    the question, or before answers that left the question asked again ("the left one")."""
    lang, history = reader.lexicon.lang, reader.history
    question = history[spoken[-1]].text
    for at in range(len(spoken) - 2, max(-1, len(spoken) - 3 - 2 * _ASKED_AGAIN), -2):
        said = history[spoken[at]]
        if said.role != "user" or not question.endswith(history[spoken[at + 1]].text):
            return None  # the question was not asked again: an older request is no longer pending
        pending = parse(lang, heard.of(said.text), reader.robot_name)
        if pending.act == "command":
            return spoken[at], pending
    return None


def _sure(outcome: Outcome) -> Outcome:
    """A request completed by a follow-up is a little less sure than one said whole."""
    return replace(outcome, confidence=0.8, more=())


def _fragment(lang: Language, p: Parse, heard: Said) -> tuple[Words, Words | None]:
    """The words of the answer ("mine, obviously": whose it is, without the interjection), and what
    a clause after it says of the thing ("..., it's Carla's"), if one does."""
    said = clauses(lang, heard)
    more = description(lang, heard.of(said[1])) if len(said) == 2 else None
    words = heard.of(said[0]).tokens if more is not None else p.words
    owners, interjections = lang.words.owners, lang.followups.interjections
    return tuple(owners.get(w, w) for w in _unapproved(lang, words) if w not in interjections), more


def _unapproved(lang: Language, words: Words) -> Words:
    """The answer without what the speaker thinks of it: "on the till counter's fine" is "on the
    till counter", "the red one is good" "the red one"."""
    if len(words) < 2 or words[-1] not in lang.followups.approving:
        return words
    if words[-2] == "is":
        return words[:-2]
    return (*words[:-2], words[-2].removesuffix("'s")) if words[-2].endswith("'s") else words


def _merged(lang: Language, fragment: Words, first: Outcome) -> Words:
    """The fragment with the pending request's phrase: "the red one" and "the cup" make "the red
    cup"; prepositions stay ("the novel" + "book from the shelf" keeps "book" as the head)."""
    if first.open_phrase:
        phrase = tuple(w for w in first.open_phrase if w not in {"the", "a", "an"})
        if not set(fragment) & lang.followups.one:
            return (*fragment, *phrase)
        return tuple(x for w in fragment for x in (phrase if w in lang.followups.one else (w,)))
    # (a fragment answering "Where should I put it?" may start with its preposition: "on the shelf")
    for loc in lang.prepositions.longest_first("place"):
        if fragment[: len(loc)] == loc:
            return fragment[len(loc) :]
    return fragment


def offer(reader: Reader, question: Utterance, said: list[str]) -> Outcome | None:
    """ "yes please" to "Would you like me to bring you a basket?": the request the robot offered,
    in the words of the person who accepts it ("bring me a basket")."""
    lang = reader.lexicon.lang
    if not accepts(lang, said):
        return None
    request = _offered(lang, expanded(lang, question.text.rstrip(" ?")))
    outcome = reader.act(parse(lang, " ".join(request), reader.robot_name)) if request else None
    if outcome is None or outcome.intent is None:
        return None
    return _sure(outcome)


def _offered(lang: Language, asked: list[str]) -> list[str]:
    """The request an offer makes, in the words of the person offered it ([] when it makes none)."""
    for lead in lang.followups.offers:
        at = next((i for i in range(len(asked)) if tuple(asked[i : i + len(lead)]) == lead), None)
        if at is not None:
            return [lang.followups.swapped.get(w, w) for w in asked[at + len(lead) :]]
    for lead in lang.followups.offers_a_thing:  # "Would you like a towel?"
        if tuple(asked[: len(lead)]) == lead and asked[len(lead) :]:
            return ["bring", "me", *asked[len(lead) :]]
    return []


def confirmation(earlier: Reader, pending: Parse, first: Outcome, question: Utterance,
                 said: list[str]) -> Outcome | None:  # fmt: skip
    """ "yes" or "no, the other one" to "Do you mean the flat brush?": the thing the robot guessed,
    or the one other thing the pending request's phrase names."""
    lang = earlier.lexicon.lang
    asked = expanded(lang, question.text.rstrip(" ?"))
    lead = next((c for c in lang.followups.confirms if tuple(asked[: len(c)]) == c), None)
    role = first.open_role
    if lead is None or role is None or not first.open_phrase:
        return None
    kinds = ROLE_KINDS.get(pending.intent or "", {}).get(role)
    if kinds is None:
        return None
    candidates = resolve(earlier.lexicon, first.open_phrase, kinds).matches
    guessed = resolve(earlier.lexicon, asked[len(lead) :], kinds).one
    if guessed is None or guessed not in candidates:
        return None
    if said[:1] == ["no"] and set(said) & lang.followups.other:  # "no the other one"
        others = [e for e in candidates if e.id != guessed.id]
        meant = others[0] if len(others) == 1 else None
    elif said[:1] != ["no"] and accepts(lang, said):
        meant = guessed
    else:
        return None
    if meant is None:
        return None
    outcome = earlier.act(pending, {role: tuple(tokens(meant.id))})
    return outcome if outcome.intent is not None else None




def correction(reader: Reader, p: Parse, heard: Said) -> Outcome | None:
    """ "sorry, I meant screen two" after "take the booster seat to screen 1": the last request again,
    with the phrase of the role that names the same kind of thing (a place for a place, a thing for
    a thing) replaced."""
    lang = reader.lexicon.lang
    fragment = _meant(lang, heard)
    if not content_words(lang, fragment):
        return None
    asked = [i for i, u in enumerate(reader.history) if u.role == "user"]
    if not asked:
        return None
    earlier = reader.within(reader.history[: asked[-1]])
    pending = parse(lang, heard.of(reader.history[asked[-1]].text), reader.robot_name)
    if pending.act != "command" or pending.intent is None:
        return None
    before = earlier.act(pending)
    slots = pending.slots
    if pending.double_object and "rest" in slots:  # "fetch Ana the mug": whose phrase is whose
        slots = earlier.refs.split_double_object(slots["rest"])
    fits: list[tuple[int, Outcome]] = []
    for role in ROLE_KINDS.get(pending.intent, {}):
        said = slots.get(role, ())
        was = before.roles.get(role)
        if not content_words(lang, said) or was is None:
            continue
        instead = _the_other(earlier, fragment, said, was, ROLE_KINDS[pending.intent][role])
        outcome = earlier.act(pending, {role: instead or _instead(lang, fragment, said)})
        now = outcome.roles.get(role)
        if outcome.intent is None or now is None or now == was:
            continue
        if any(v == now for r, v in outcome.roles.items() if r != role):
            continue  # the red mug put on the red mug: the other role was meant
        old, new = earlier.snapshot.get(was), earlier.snapshot.get(now)
        if old is None or new is None or old.kind != new.kind:
            continue  # "I meant screen two" corrects a place, never the thing carried there
        fits.append((len(set(old.classes) & set(new.classes)), outcome))
    fits.sort(key=lambda f: -f[0])
    if not fits or (len(fits) > 1 and fits[0][0] == fits[1][0]):
        return None
    return _sure(fits[0][1])


def _the_other(earlier: Reader, fragment: Words, said: Words, was: str,
               kinds: frozenset[Kind]) -> Words | None:  # fmt: skip
    """ "no, the other one" after "bring me the black umbrella": the one other thing the head of the
    phrase names (the red umbrella), as its id; None when that is not what was said or several are."""
    lang = earlier.lexicon.lang
    other, one = lang.followups.other, lang.followups.one
    if not set(fragment) & other or not set(content_words(lang, fragment)) <= other | one:
        return None
    named = resolve(earlier.lexicon, _instead(lang, ("the", "one"), said), kinds).matches
    others = [e for e in named if e.id != was]
    return tuple(tokens(others[0].id)) if len(others) == 1 and len(named) == 2 else None


def _meant(lang: Language, heard: Said) -> Words:
    """What a correction says was meant ("I meant screen two", "not the shed, the porch", "no, the
    other one", "no, the blue one"), without the preposition of a place; () when it says none."""
    softening = lang.followups.softening
    parts = [strip_politeness(lang, [w for w in plain(lang, heard.of(part)) if w not in softening])
             for part in heard.text.split(",")]  # fmt: skip
    words = [w for part in parts for w in part]
    lead = next((c for c in lang.followups.correcting if tuple(words[: len(c)]) == c), None)
    fragment = tuple(words[len(lead) :]) if lead is not None else _not_that(lang, tuple(words))
    other, one = lang.followups.other, lang.followups.one
    if lead is None and set(words) & other and set(content_words(lang, words)) <= other | one:
        fragment = tuple(words)  # "no, the other one"
    elif lead is None and not fragment and _said_no(lang, heard) and set(words) & one:
        # "no, the blue one", "nope, the red one": the one meant, told apart by what it is
        fragment = tuple(w for w in words if lang.followups.no.get(w, w) != "no")
    if len(parts) == 2 and parts[0][:1] == ["not"] and parts[1]:  # "not the shed, the porch"
        fragment = tuple(parts[1])
    for loc in lang.prepositions.longest_first("place"):  # "I meant on the shelf"
        if fragment[: len(loc)] == loc and fragment[len(loc) :]:
            return fragment[len(loc) :]
    return fragment


def _said_no(lang: Language, heard: Said) -> bool:
    """Whether the words start with a no ("no, the blue one", "nope, the big one")."""
    first = plain(lang, heard)[:1]
    return bool(first) and lang.followups.no.get(first[0], first[0]) == "no"


def _not_that(lang: Language, words: Words) -> Words:
    """ "not the shed, the porch" or "the porch, not the shed": the phrase meant (() if none is)."""
    if "not" not in words:
        return ()
    at = words.index("not")
    if at > 0:
        return words[:at]
    np_start = lang.words.np_start
    starts = (j for j in range(2, len(words)) if words[j] in np_start and words[j - 1] not in np_start)
    again = next(starts, None)
    return words[again:] if again is not None else ()


def _instead(lang: Language, fragment: Words, said: Words) -> Words:
    """The fragment, its "one" said with the head of the phrase it replaces ("the red one" for "the
    blue cup": the red cup)."""
    core: list[str] = []
    for w in said:
        if w in lang.modifier_start and core:
            break
        core.append(w)
    head = content_words(lang, core)[-1:] if content_words(lang, core) else []
    return tuple(x for w in fragment for x in (head if w in lang.followups.one and head else [w]))


def continuation(reader: Reader, p: Parse, heard: Said) -> Outcome | None:
    """ "and the soup goes to table two", "and the soup to table two" after "take the steak to table
    four": the request just made (a bringing) again, for another thing and place. Alone, "X goes to
    Y" says no request."""
    lang = reader.lexicon.lang
    words = tuple(strip_politeness(lang, plain(lang, heard)))
    found = where_it_goes(lang, words)
    if found is None and "to" in words[1:-1]:  # said without its verb
        at = words.index("to")
        found = words[:at], ("to",), words[at + 1 :]
    if found is None or found[1] != ("to",):
        return None
    asked = [i for i, u in enumerate(reader.history) if u.role == "user"]
    if not asked:
        return None
    pending = parse(lang, heard.of(reader.history[asked[-1]].text), reader.robot_name)
    if pending.act != "command" or pending.intent != I.BRING_OBJECT:
        return None
    thing, _, place = found
    again = Parse("command", I.BRING_OBJECT, {"object": thing, "recipient": place}, words=(*thing, *place),
                  marks={"recipient": "to"})  # fmt: skip
    outcome = reader.act(again)
    return _sure(outcome) if outcome.intent is not None else None


#: What an utterance in which the grammar reads no act may be, in the order tried: an answer to the
#: robot's question, a correction of the request just made, the same request for another thing.
FOLLOW_UPS: tuple[Callable[[Reader, Parse, Said], Outcome | None], ...] = (
    follow_up, correction, continuation,
)  # fmt: skip


def followed_up(reader: Reader, p: Parse, heard: Said) -> Outcome | None:
    """What the first follow-up that reads the utterance made of it (`FOLLOW_UPS`)."""
    for read in FOLLOW_UPS:
        outcome = read(reader, p, heard)
        if outcome is not None:
            return outcome
    return None
