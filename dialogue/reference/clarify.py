"""Clarifying questions built from what tells the candidates apart: label, colour, support, zone."""

from __future__ import annotations

from collections.abc import Callable, Sequence

from dialogue.reference.grounding import Entity, Snapshot

MAX_OPTIONS = 4


def common_noun(candidates: Sequence[Entity]) -> str:
    """The most specific class name all candidates share ("cup"), else "one"."""
    if not candidates:
        return "one"
    shared = [n for n in candidates[0].class_names if all(n in c.class_names for c in candidates[1:])]
    return shared[0] if shared else "one"


def _distinct(values: Sequence[str | None]) -> bool:
    return all(v is not None for v in values) and len(set(values)) == len(values)


def describe_options(snapshot: Snapshot, candidates: Sequence[Entity]) -> list[str]:
    """One short description per candidate that is enough to tell it from the others."""
    noun = common_noun(candidates)
    labels = [c.labels[0] if c.labels else None for c in candidates]
    features: list[Callable[[Entity], str | None]] = []
    colours = [c.colour for c in candidates]
    supports = [c.support for c in candidates]
    zones = [c.zone for c in candidates]
    if _distinct([lbl.lower() if lbl else None for lbl in labels]):
        return [f"the {c.labels[0]}" for c in candidates]
    if _distinct(colours):
        features.append(lambda c: f"the {c.colour} one")
    if _distinct(supports):
        features.append(lambda c: f"the one on the {snapshot.name_of(c.support or '')}")
    if _distinct(zones):
        features.append(lambda c: f"the one in the {snapshot.name_of(c.zone or '')}")
    if _distinct([c.owner for c in candidates]):
        features.append(lambda c: f"{snapshot.name_of(c.owner or '')}'s")
    if not features:  # each by what the KB says of it: "Ola's or the one in the shed"
        mixed = [_said_of(snapshot, c) for c in candidates]
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
        where = f" on the {snapshot.name_of(c.support)}" if c.support else ""
        out.append(f"the {c.name if c.labels else noun}{where} ({c.id})")
    return out


def _said_of(snapshot: Snapshot, c: Entity) -> str | None:
    """The first thing the KB says of a candidate that a person could answer with."""
    if c.colour:
        return f"the {c.colour} one"
    if c.owner:
        return f"{snapshot.name_of(c.owner)}'s"
    if c.support:
        return f"the one on the {snapshot.name_of(c.support)}"
    return f"the one in the {snapshot.name_of(c.zone)}" if c.zone else None


def _join(options: Sequence[str]) -> str:
    if len(options) == 1:
        return options[0]
    return ", ".join(options[:-1]) + " or " + options[-1]


def question(snapshot: Snapshot, candidates: Sequence[Entity], noun: str | None = None) -> str:
    """E.g. "Which cup do you mean: the red cup or the blue cup?"; `noun` is the word said for them
    all, when the caller has one ("Which drink...", not the classes' "Which location...")."""
    noun = noun or common_noun(candidates)
    shown = list(candidates[:MAX_OPTIONS])
    options = describe_options(snapshot, shown)
    if len(candidates) > MAX_OPTIONS:
        options.append("another one")
    head = f"Which {noun}" if noun != "one" else "Which one"
    return f"{head} do you mean: {_join(options)}?"
