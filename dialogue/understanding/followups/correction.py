"""A correction of the request just made: "sorry, I meant screen two" after "take the booster seat
to screen 1", "no, the blue one", "no, the other one"; the phrase of the role that names the same kind
of thing replaced."""

from __future__ import annotations

from dataclasses import dataclass

from dialogue import intents as I
from dialogue.reference.english import Words, tokens
from dialogue.reference.grounding import Kind
from dialogue.reference.resolution import ROLE_KINDS, content_words, resolve
from dialogue.understanding.context import Reader
from dialogue.understanding.language import Language
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.parsed import Parse
from dialogue.understanding.replies import say
from dialogue.understanding.requests.commands import parse
from dialogue.understanding.said import Said
from dialogue.understanding.speech.plain import plain, strip_politeness


def correction(reader: Reader, p: Parse, heard: Said) -> Outcome | None:
    """ "sorry, I meant screen two" after "take the booster seat to screen 1": the last request again,
    with the phrase of the role that names the same kind of thing (a place for a place, a thing for
    a thing) replaced; after a correction, the request as it corrected it ("no, the blue one" then
    "no, the other one")."""
    corrected = _corrected(reader, heard, _IN_A_ROW)
    return corrected.outcome.followed_up() if corrected is not None else None


#: Acts a correction of the request just made may read as ("make that the study": an activity;
#: "wait, no, on the bookcase": a refusal; "thanks! now the apple too": thanks): read as the
#: correction when one fits.
_CORRECTABLE = frozenset({"command", "negated", "thanks"})


def corrected_first(reader: Reader, p: Parse, heard: Said) -> Outcome | None:
    """What is read as a correction before the words are read as a request of their own: words that
    open as one ("make that the study": an act `_CORRECTABLE`, when the correction fits), and one
    more for the request just made ("oh and the biscuits too" after a request: that request for one
    more thing, or, when which of its roles the phrase replaces is not clear, not understood: never
    a bringing guessed from the thing alone)."""
    lang = reader.lexicon.lang
    if not opens_correction(lang, heard):
        return None
    if p.act in _CORRECTABLE:
        return correction(reader, p, heard)
    added = _added(lang, heard) if p.act == "unknown" else ()
    if not added or not any(u.role == "user" for u in reader.history):
        return None
    corrected = correction(reader, p, heard)
    if corrected is not None:
        return corrected
    # (words the KB does not name, "and the rake goes to the porch", are left to the other follow-ups)
    named = all(reader.lexicon.knows(w) for w in content_words(lang, added))
    return Outcome(say(lang, "sorry.not_understood"), understood=False) if named else None


#: A carrying's roles as the guiding it was read as ("take Daniel to the hallway": Daniel is whom
#: the robot guides, the hallway where to): the role a correction of its phrase corrects.
_GUIDED = {"object": "recipient", "recipient": "goal"}

#: How many corrections in a row may stand between a correction and the request it corrects.
_IN_A_ROW = 3


@dataclass(frozen=True)
class _Standing:
    """The request a correction corrects: the reader before it was said, its parse, the roles that
    corrections replaced in it (by their words) and what it came to."""

    earlier: Reader
    pending: Parse
    replaced: dict[str, Words]
    outcome: Outcome


def _standing(reader: Reader, heard: Said, depth: int) -> _Standing | None:
    """The request the person's last words made, or, when they corrected one, that request as they
    corrected it (at most `depth` corrections back)."""
    lang = reader.lexicon.lang
    asked = [i for i, u in enumerate(reader.history) if u.role == "user"]
    if not asked:
        return None
    earlier = reader.within(reader.history[: asked[-1]])
    said = heard.of(reader.history[asked[-1]].text)
    pending = parse(lang, said, reader.robot_name)
    if pending.act == "command" and pending.intent is not None:
        return _Standing(earlier, pending, {}, earlier.act(pending))
    return _corrected(earlier, said, depth - 1) if depth > 0 else None


def _corrected(reader: Reader, heard: Said, depth: int) -> _Standing | None:
    """The standing request with the phrase the correction's words replace, if they replace one."""
    lang = reader.lexicon.lang
    fragment, placed = _meant(lang, heard)
    if not content_words(lang, fragment):
        return None
    standing = _standing(reader, heard, depth)
    if standing is None:
        return None
    earlier, pending, before = standing.earlier, standing.pending, standing.outcome
    assert pending.intent is not None  # (a standing request is a command)
    slots = pending.slots
    if pending.double_object and "rest" in slots:  # "fetch Ana the mug": whose phrase is whose
        slots = earlier.refs.split_double_object(slots["rest"])
    fits: list[tuple[int, _Standing]] = []
    unsettled = 0
    for role in ROLE_KINDS.get(pending.intent, {}):
        if placed and role == "object":
            continue  # ("no, on the luggage rack": where it goes, never the thing)
        said = slots.get(role, ())
        out = _GUIDED.get(role, role) if before.intent == I.GUIDE != pending.intent else role
        was = before.roles.get(out)
        if not content_words(lang, said) or was is None:
            continue
        instead = _the_other(earlier, fragment, said, was, ROLE_KINDS[pending.intent][role])
        replaced = {**standing.replaced, role: instead or _instead(lang, fragment, said)}
        outcome = earlier.act(pending, replaced)
        now = outcome.roles.get(out)
        unsettled += outcome.clarify  # (a role the words name several things of)
        if outcome.intent is None or now is None or now == was:
            continue
        if any(v == now for r, v in outcome.roles.items() if r != out):
            continue  # the red mug put on the red mug: the other role was meant
        old, new = earlier.snapshot.get(was), earlier.snapshot.get(now)
        if old is None or new is None or old.kind != new.kind:
            continue  # "I meant screen two" corrects a place, never the thing carried there
        shared = len(set(old.classes) & set(new.classes))
        fits.append((shared, _Standing(earlier, pending, replaced, outcome)))
    fits.sort(key=lambda f: -f[0])
    if not fits or (len(fits) > 1 and fits[0][0] == fits[1][0]):
        return None
    named = not set(fragment) & lang.followups.one  # ("the blue one": of the kind of the phrase it replaces)
    if len(fits) + (unsettled if named else 0) > 1 and _again(lang, heard):
        return None  # ("do the same with the bowl": a bowl put there, or the thing put on the bowl)
    return fits[0][1]


def _the_other(earlier: Reader, fragment: Words, said: Words, was: str,
               kinds: frozenset[Kind]) -> Words | None:  # fmt: skip
    """ "no, the other one" after "bring me the black umbrella": the one other thing the head of the
    phrase names (the red umbrella), as its id; None when that is not what was said or several are."""
    lang = earlier.lexicon.lang
    other, one = lang.followups.other, lang.followups.one
    if not set(fragment) & other or not set(content_words(lang, fragment)) <= other | one:
        return None
    named = resolve(earlier.lexicon, _instead(lang, lang.followups.the_other, said), kinds).matches
    others = [e for e in named if e.id != was]
    return tuple(tokens(others[0].id)) if len(others) == 1 and len(named) == 2 else None


def _again(lang: Language, heard: Said) -> bool:
    """Whether the words ask for the request again with something else ("now do the same with the
    bowl"): what they name may be any of its roles, and no likelier one is guessed."""
    words = tuple(strip_politeness(lang, plain(lang, heard)))
    return any(words[: len(a)] == a for a in lang.followups.again) or bool(_added(lang, heard))


def adds_one_more(lang: Language, heard: Said) -> bool:
    """Whether the words say one more thing for the request just made ("and then the teddy too"):
    read as the request again before as a request of their own, which would lose its other roles
    (the teddy brought to the speaker rather than to whom the request brought the book)."""
    return bool(_added(lang, heard))


def _added(lang: Language, heard: Said) -> Words:
    """ "Now the apple too", "and Zara as well": the phrase said as one more for the request just
    made (() when the words say none that way)."""
    said = tuple(w for w in plain(lang, heard) if w not in lang.followups.softening)
    while said[-1:] and said[-1] in lang.followups.interjections:  # ("and the keys too please")
        said = said[:-1]
    end = next((a for a in lang.followups.additive if len(said) > len(a) and said[-len(a) :] == a), None)
    if end is None:  # "and also the apple": said so by its first words alone
        alone = lang.followups.additive_alone
        lead = next((a for a in alone if len(said) > len(a) and said[: len(a)] == a), ())
        return said[len(lead) :] if lead and _a_phrase(lang, said[len(lead) :]) else ()
    phrase = said[: -len(end)]
    lead = next((a for a in lang.followups.additive_leads if phrase[: len(a)] == a), ())
    return phrase[len(lead) :]



def _meant(lang: Language, heard: Said) -> tuple[Words, bool]:
    """What a correction says was meant ("I meant screen two", "not the shed, the porch", "no, the
    other one", "no, the blue one"), without the preposition of a place, and whether it was said
    with one; () when it says none."""
    softening = lang.followups.softening
    parts = [strip_politeness(lang, [w for w in plain(lang, heard.of(part)) if w not in softening])
             for part in heard.text.split(",")]  # fmt: skip
    words = [w for part in parts for w in part]
    leads = (*lang.followups.correcting, *lang.followups.again)
    lead = next((c for c in leads if tuple(words[: len(c)]) == c), None)
    fragment = tuple(words[len(lead) :]) if lead is not None else _not_that(lang, tuple(words))
    if lead is None and not fragment:
        fragment = _added(lang, heard) or _said_instead(lang, heard, tuple(words))  # "now the apple too"
    other, one = lang.followups.other, lang.followups.one
    if lead is None and set(words) & other and set(content_words(lang, words)) <= other | one:
        fragment = tuple(words)  # "no, the other one"
    elif lead is None and not fragment and _said_no(lang, heard):
        # "no, the blue one", "wait, no, on the bookcase": the one meant, told apart by what it is
        rest = tuple(w for w in words if lang.followups.no.get(w, w) != "no")
        fragment = rest if set(words) & one or _a_phrase(lang, rest) else ()
    if len(parts) == 2 and parts[0][:1] == ["not"] and parts[1]:  # "not the shed, the porch"
        fragment = tuple(parts[1])
    for loc in lang.prepositions.longest_first("place"):  # "I meant on the shelf"
        if fragment[: len(loc)] == loc and fragment[len(loc) :]:
            return fragment[len(loc) :], True
    return fragment, False


def _said_instead(lang: Language, heard: Said, words: Words) -> Words:
    """ "no wait, take Maya instead": the request said again with one role's phrase, said to be
    meant instead; that phrase (() when the words say no request with one role)."""
    end = next((e for e in lang.followups.instead if len(words) > len(e) and words[-len(e) :] == e), None)
    if end is None:
        return ()
    again = parse(lang, heard.of(" ".join(words[: -len(end)])), "")
    said = [w for w in again.slots.values() if w]
    return said[0] if again.act == "command" and len(said) == 1 else ()


def _a_phrase(lang: Language, words: Words) -> bool:
    """Whether the words are a noun phrase or a place said with its preposition ("the study", "on
    the bookcase"), not a clause ("that's Daniel's, mine is the orange one")."""
    places = lang.prepositions.longest_first("place")
    start = next((len(p) for p in places if words[: len(p)] == p), 0)
    phrase = words[start:]
    said = lang.words.head_noun
    return bool(phrase) and phrase[0] in said.new_phrase and not set(phrase) & said.clause_words


def _said_no(lang: Language, heard: Said) -> bool:
    """Whether the words start with a no, maybe softened ("no, the blue one", "wait, no, the big
    one")."""
    no, softening = lang.followups.no, lang.followups.softening
    first = next((w for w in plain(lang, heard) if no.get(w, w) == "no" or w not in softening), None)
    return first is not None and no.get(first, first) == "no"


def opens_correction(lang: Language, heard: Said) -> bool:
    """Whether the words open as a correction does ("make that the study", "wait, no, on the
    bookcase", "thanks! now the apple too"): read as one before as a request, a refusal or thanks of
    their own, if one fits; "take Maya instead", its "no wait" taken as a false start, too."""
    words = tuple(w for w in plain(lang, heard) if w not in lang.followups.softening)
    opened = _said_no(lang, heard) or bool(_added(lang, heard)) or bool(_said_instead(lang, heard, words))
    return opened or any(words[: len(c)] == c for c in lang.followups.correcting)


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
