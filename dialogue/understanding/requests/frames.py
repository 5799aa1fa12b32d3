"""The grammar of requests as data: verb frames, read from the language's `frames.toml`.

A frame says which verb phrases ask for an intent and how the words after the verb fill its roles:
the role of the words right after the verb (`direct`), the prepositions that introduce each other
role (`slots`, found in any order: "bring the tray to Ana" and "bring to Ana the tray"), the
particles dropped around them ("pick *up*", "head *over* to"), the role that a bare "here"/"there"
fills, and which roles must be said for the frame to apply. Verbs are lemmas, so "picking", "took"
and "puts" need no frame of their own; multi-word verbs ("get hold of", "make your way") are phrases.
What a frame cannot say is a small function of dialogue.understanding.requests.constructions, named
in the frame.

Frames are tried longest verb phrase first, then in the file's order; the first that fits wins. To
add a verb, add it to a frame (or add a frame).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

from dialogue.reference.english import Words, phrases, word_set
from dialogue.understanding.language import Language, LanguageError
from dialogue.understanding.parsed import Parse
from dialogue.understanding.requests import constructions as C
from dialogue.understanding.requests import needs, telling
from dialogue.understanding.tables.frames import FrameRow

#: How a frame makes the free-form text of its intent from (its language, the verb's words, the words
#: after it).
Text = Callable[[Language, Words, Words], str | None]
Special = Callable[[C.Framed], Parse | None]


def _named(name: str) -> Text:
    return lambda lang, verb, rest: name


def _verb(lang: Language, verb: Words, rest: Words) -> str:
    return " ".join(verb)


def _activity(lang: Language, verb: Words, rest: Words) -> str | None:
    """ "play a game with me" -> "play_game"; "start (to) vacuum" -> "vacuum"."""
    words = rest[1:] if rest[:1] == ("to",) else rest
    words = words[: words.index("for")] if "for" in words[1:] else words  # ("story time for the little ones")
    said = [w for w in words if w not in lang.requests.activity_filler]
    if said[:1] and said[0] in lang.requests.activity_anaphora:  # "do the same with the blue one"
        return None
    return "_".join(said) or None


def _doing(lang: Language, verb: Words, rest: Words) -> str | None:
    """ "water the plants" -> "water_plants": the verb names the activity."""
    return _activity(lang, verb, (*verb, *rest))


def _stopping(lang: Language, verb: Words, rest: Words) -> str | None:
    return "_".join(w for w in rest if w not in lang.requests.stop_filler) or None


#: How a frame's text is made, by the name the file gives it.
TEXTS: dict[str, Text] = {"verb": _verb, "activity": _activity, "doing": _doing, "stopping": _stopping}
#: The constructions a frame may name (`special`), and those tried before any verb is read.
SPECIALS: dict[str, Special] = {
    "everyone": C.everyone, "speech": telling.speech, "letting_know": telling.letting_know,
    "helping": C.helping, "a_hand": C.a_hand, "showing": C.showing, "asking": C.asking, "company": C.company,
}  # fmt: skip
WHOLE_UTTERANCE: dict[str, Special] = {
    "need": needs.need, "their_pursuit": needs.their_pursuit, "going": C.going, "wanting": C.wanting,
    "their_wish": C.their_wish, "belonging": C.belonging, "enough": C.enough,
}  # fmt: skip


@dataclass(frozen=True)
class Frame:
    #: Verb phrases ("grab|pick|get hold of"): the first word is a lemma, the others as said.
    verbs: str
    intent: str | None = None
    #: The role of the words right after the verb, with no preposition ("bring *the cup* to Ana").
    #: A role the intent does not ground ("extra", "manner") takes words that change nothing.
    direct: str | None = None
    #: Each other role and the prepositions that introduce it ("to|towards|for").
    slots: dict[str, str] = field(default_factory=dict)
    #: Words dropped next to the verb, at the end of a phrase or before a preposition.
    particles: str = ""
    #: The role a bare "here" (the speaker) or "there" (the place just spoken of) fills.
    here: str | None = None
    #: Only "there" fills it ("wait there": the place spoken of; "wait here" is to stay put).
    there_only: bool = False
    #: Only "here" fills it ("pop it over here": to the speaker; "over there" is where to put it).
    here_only: bool = False
    #: The direct words may start with the recipient: "me"/"us" only ("get me a cup"), anyone
    #: ("give Ines her phone": split against the KB by the interpreter), or anyone said before a
    #: noun phrase of its own ("get Ines her phone", but "get the phone").
    dative: Literal["me", "any", "before"] | None = None
    #: The only words the direct role may be ("take *me* to the kitchen").
    only: frozenset[str] | None = None
    #: Roles that must be said for the frame to apply (else the next frame is tried).
    requires: tuple[str, ...] = ()
    #: A role's value when it is not said (it is then marked implicit).
    defaults: dict[str, Words] = field(default_factory=dict)
    #: The verb phrase is all there is ("sleep"), not the start of a longer request.
    whole: bool = False
    text: Text | None = None
    #: A function for what the frame cannot say; it returns None when it does not apply.
    special: Special | None = None
    #: "go (and) get the cup": a verb after this one is the request.
    serial: bool = False


_GROUP = re.compile(r"@([\w-]+)")


def _expanded(lang: Language, text: str, seen: tuple[str, ...] = ()) -> str:
    """The text with each "@name" replaced: a group of the file, or the prepositions that have a use."""

    def group(m: re.Match[str]) -> str:
        name = m.group(1)
        found = lang.prepositions.having(name)
        if name in lang.frames.groups and found:
            raise LanguageError(f"{lang.code}/frames.toml: {name!r} is a group and a use of prepositions")
        if name in lang.frames.groups and name not in seen:
            return _expanded(lang, lang.frames.groups[name], (*seen, name))
        if not found:
            raise LanguageError(f"{lang.code}/frames.toml: no group or preposition use {name!r} ({text!r})")
        return "|".join(" ".join(p) for p in found)

    return _GROUP.sub(group, text)


def _frame(lang: Language, row: FrameRow) -> Frame:
    if row.special is not None and row.special not in SPECIALS:
        raise LanguageError(f"{lang.code}/frames.toml: no construction {row.special!r} ({row.verbs!r})")
    only = lang.words.me if row.only == "@me" else word_set(_expanded(lang, row.only)) if row.only else None
    text = TEXTS[row.text] if row.text is not None else _named(row.named) if row.named is not None else None
    return Frame(
        verbs=_expanded(lang, row.verbs), intent=row.intent, direct=row.direct,
        slots={role: _expanded(lang, preps) for role, preps in row.slots.items()},
        particles=_expanded(lang, row.particles), here=row.here,
        there_only=row.there_only, here_only=row.here_only,
        dative=row.dative, only=only, requires=row.requires, defaults=dict(row.defaults), whole=row.whole,
        text=text, special=SPECIALS[row.special] if row.special is not None else None, serial=row.serial,
    )  # fmt: skip


def frames(lang: Language) -> tuple[Frame, ...]:
    """The language's verb frames, in the file's order (read once per language)."""
    return lang.derived(_frames)


def _frames(lang: Language) -> tuple[Frame, ...]:
    return tuple(_frame(lang, row) for row in lang.frames.frame)


def constructions(lang: Language) -> tuple[Special, ...]:
    """What the whole utterance may say before any verb is read ("I'm parched", "I want the apple")."""
    return lang.derived(_constructions)


def _constructions(lang: Language) -> tuple[Special, ...]:
    unknown = [name for name in lang.frames.constructions if name not in WHOLE_UTTERANCE]
    if unknown:
        raise LanguageError(f"{lang.code}/frames.toml: no construction {unknown[0]!r}")
    return tuple(WHOLE_UTTERANCE[name] for name in lang.frames.constructions)


@dataclass(frozen=True)
class Row:
    """A frame with its strings read into words (once, on first use)."""

    frame: Frame
    order: int
    particles: frozenset[str]
    slots: tuple[tuple[Words, str], ...]  # (preposition, role), longest preposition first


def verb_index(lang: Language) -> dict[str, tuple[tuple[Words, Row], ...]]:
    """First word of a verb phrase -> (phrase, row), longest phrase first, then in the frames' order."""
    return lang.derived(_verb_index)


def _verb_index(lang: Language) -> dict[str, tuple[tuple[Words, Row], ...]]:
    index: dict[str, list[tuple[Words, Row]]] = {}
    for order, frame in enumerate(frames(lang)):
        slots = sorted(((p, role) for role, preps in frame.slots.items() for p in phrases(preps)),
                       key=lambda s: -len(s[0]))  # fmt: skip
        row = Row(frame, order, word_set(frame.particles), tuple(slots))
        for verb in phrases(frame.verbs):
            index.setdefault(verb[0], []).append((verb, row))
    return {w: tuple(sorted(rows, key=lambda r: (-len(r[0]), r[1].order))) for w, rows in index.items()}


def verbs(lang: Language) -> frozenset[str]:
    """Every word a request may start with (the first words of the frames' verb phrases)."""
    return lang.derived(_verbs)


def _verbs(lang: Language) -> frozenset[str]:
    return frozenset(verb_index(lang))


def known_verbs(lang: Language) -> frozenset[str]:
    """The frames' verbs and the actions the robot has no intent for ("find", "open")."""
    return lang.derived(_known_verbs)


def _known_verbs(lang: Language) -> frozenset[str]:
    return verbs(lang) | lang.requests.no_intent_verbs
