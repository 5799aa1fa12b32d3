"""Clarifying questions built from what tells the candidates apart: label, colour, support, zone
(said in the language's words: its `replies.toml`, [clarify])."""

from __future__ import annotations

from collections.abc import Callable, Sequence

from dialogue.reference.grounding import Entity, Snapshot
from dialogue.understanding.language import Language
from dialogue.understanding.replies import say

MAX_OPTIONS = 4


def common_noun(lang: Language, candidates: Sequence[Entity]) -> str:
    """The most specific class name all candidates share ("cup"), else the word for any ("one")."""
    one = say(lang, "clarify.one")
    if not candidates:
        return one
    shared = [n for n in candidates[0].class_names if all(n in c.class_names for c in candidates[1:])]
    return shared[0] if shared else one


def _distinct(values: Sequence[str | None]) -> bool:
    return all(v is not None for v in values) and len(set(values)) == len(values)


def describe_options(lang: Language, snapshot: Snapshot, candidates: Sequence[Entity]) -> list[str]:
    """One short description per candidate that is enough to tell it from the others."""
    noun = common_noun(lang, candidates)
    labels = [c.labels[0] if c.labels else None for c in candidates]
    features: list[Callable[[Entity], str | None]] = []
    colours = [c.colour for c in candidates]
    supports = [c.support for c in candidates]
    zones = [c.zone for c in candidates]
    if _distinct([lbl.lower() if lbl else None for lbl in labels]):
        return [say(lang, "clarify.label", label=c.labels[0]) for c in candidates]
    if _distinct(colours):
        features.append(lambda c: say(lang, "clarify.coloured", colour=c.colour))
    if _distinct(supports):
        features.append(lambda c: say(lang, "clarify.on", place=snapshot.name_of(c.support or "")))
    if _distinct(zones):
        features.append(lambda c: say(lang, "clarify.in", place=snapshot.name_of(c.zone or "")))
    if _distinct([c.owner for c in candidates]):
        features.append(lambda c: say(lang, "clarify.owned", owner=snapshot.name_of(c.owner or "")))
    if not features:  # each by what the KB says of it: "Ola's or the one in the shed"
        mixed = [_said_of(lang, snapshot, c) for c in candidates]
        if _distinct(mixed):
            return [m or "" for m in mixed]
    if features:
        out = []
        for c in candidates:
            text = features[0](c) or ""
            out.append(text)
        return out
    # Nothing in the KB tells them apart: name them by label/support and id so the answer can use either.
    out = []
    for c in candidates:
        where = say(lang, "clarify.by_id_on", place=snapshot.name_of(c.support)) if c.support else ""
        out.append(say(lang, "clarify.by_id", name=c.name if c.labels else noun, where=where, id=c.id))
    return out


def _said_of(lang: Language, snapshot: Snapshot, c: Entity) -> str | None:
    """The first thing the KB says of a candidate that a person could answer with."""
    if c.colour:
        return say(lang, "clarify.coloured", colour=c.colour)
    if c.owner:
        return say(lang, "clarify.owned", owner=snapshot.name_of(c.owner))
    if c.support:
        return say(lang, "clarify.on", place=snapshot.name_of(c.support))
    return say(lang, "clarify.in", place=snapshot.name_of(c.zone)) if c.zone else None


def join(lang: Language, options: Sequence[str]) -> str:
    """Options said one or another ("the red cup, the blue cup or the green cup")."""
    if len(options) == 1:
        return options[0]
    return say(lang, "naming.separator").join(options[:-1]) + say(lang, "clarify.or") + options[-1]


def question(
    lang: Language, snapshot: Snapshot, candidates: Sequence[Entity], noun: str | None = None
) -> str:
    """E.g. "Which cup do you mean: the red cup or the blue cup?"; `noun` is the word said for them
    all, when the caller has one ("Which drink...", not the classes' "Which location...")."""
    noun = noun or common_noun(lang, candidates)
    shown = list(candidates[:MAX_OPTIONS])
    options = describe_options(lang, snapshot, shown)
    if len(candidates) > MAX_OPTIONS:
        options.append(say(lang, "clarify.another"))
    if noun != say(lang, "clarify.one"):
        return say(lang, "clarify.which", noun=noun, options=join(lang, options))
    return say(lang, "clarify.which_one", options=join(lang, options))
