"""The situation as short natural sentences for the prompt: bounded, deterministic, ids in brackets.

Class names are readable labels and things are named by their label when they have one (D17); the
id in brackets is what the model must use in intent roles. Each fact is said once: the things the
robot sees are listed under the zone they are in, the zone named once for all of them (every token
of the situation is evaluated again each turn).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from dialogue.reference.grounding import Entity, Snapshot
from dialogue.reference.relevance import ranked

MAX_LINES = 40
MAX_CHARS = 3000
#: Entities considered when the caller ranked none (the engine passes its own share).
MAX_ENTITIES = 300


def article(noun: str) -> str:
    return f"an {noun}" if noun[:1].lower() in "aeiou" else f"a {noun}"


def noun_phrase(snapshot: Snapshot, entity: Entity) -> str:
    """ "the red cup [cup_red], a cup" or "a cup [cup_1]" or "Maria [person_maria]"."""
    cls = entity.class_names[0] if entity.class_names else None
    if entity.kind == "person":
        return f"{entity.name} [{entity.id}]" if entity.labels else f"a person [{entity.id}]"
    if entity.labels:
        label = entity.labels[0]
        head = label if entity.kind == "zone" else f"the {label}"
        if cls and cls != label.lower() and entity.kind != "zone":
            return f"{head} [{entity.id}], {article(cls)}"
        return f"{head} [{entity.id}]"
    return f"{article(cls or 'thing')} [{entity.id}]"


def place_phrase(snapshot: Snapshot, entity: Entity, zone: bool = True) -> str:
    """Its colour, support, zone (unless said already: `zone` False) and owner."""
    parts = []
    if entity.colour:
        parts.append(entity.colour)
    if entity.support:
        parts.append(f"on the {snapshot.name_of(entity.support)} [{entity.support}]")
    if entity.zone and zone:
        parts.append(f"in the {snapshot.name_of(entity.zone)} [{entity.zone}]")
    owner = snapshot.get(entity.owner) if entity.owner else None
    if owner is not None:  # the model needs it to read "my phone" or "Ines's phone"
        parts.append(f"belongs to {noun_phrase(snapshot, owner)}")
    return (", " + ", ".join(parts)) if parts else ""


@dataclass(frozen=True)
class Description:
    lines: tuple[str, ...]
    truncated: int

    @property
    def text(self) -> str:
        tail = [f"({self.truncated} more things are not listed.)"] if self.truncated else []
        return "\n".join([*self.lines, *tail])


def describe(snapshot: Snapshot, speaker: str, focus: Sequence[Entity] | None = None) -> Description:
    """Who speaks, who is here, what the robot sees, known places and things not seen now: of the
    `focus` entities (most relevant first), by default the snapshot's most relevant ones."""
    pool = ranked(snapshot, speaker, MAX_ENTITIES) if focus is None else focus
    lines: list[str | None] = []
    speaking = snapshot.get(speaker)
    if speaking is not None and speaking.kind == "person":
        lines.append(f"{noun_phrase(snapshot, speaking)} is speaking to you.")
    else:
        lines.append(f"The person speaking to you has the id [{speaker}].")
    robot = snapshot.get(snapshot.robot)
    if robot is not None and robot.zone:
        lines.append(f"You are in the {snapshot.name_of(robot.zone)} [{robot.zone}].")
    people = [e for e in pool if e.kind == "person" and e.id != speaker]
    present = [e for e in people if e.seen]
    absent = [e for e in people if not e.seen]
    if present:
        lines.append("You see " + _and([noun_phrase(snapshot, e) for e in present]) + ".")
    engaged = [e for e in pool if e.kind == "person" and e.engagement in ("engaging", "engaged")]
    if engaged:
        lines.append("Engaged with you now: " + _and([noun_phrase(snapshot, e) for e in engaged]) + ".")
    if absent:
        lines.append("You know " + _and([noun_phrase(snapshot, e) for e in absent]) + ", not here now.")
    things = [e for e in pool if e.kind == "thing"]
    # Lines past MAX_LINES are never shown, only counted: they are not rendered.
    by_zone: dict[str | None, list[Entity]] = {}
    for e in things:
        if e.seen:
            by_zone.setdefault(e.zone, []).append(e)
    for zone, seen in by_zone.items():
        where = f" in the {snapshot.name_of(zone)} [{zone}]" if zone else ""
        lines.append(f"You see{where}:" if len(lines) < MAX_LINES - 1 else None)
        for e in seen:
            lines.append(f"- {noun_phrase(snapshot, e)}{place_phrase(snapshot, e, zone=False)}"
                         if len(lines) < MAX_LINES else None)
    zones = [e for e in pool if e.kind == "zone"]
    if zones:
        lines.append("Places: " + _and([noun_phrase(snapshot, e) for e in zones]) + "."
                     if len(lines) < MAX_LINES else None)
    unseen = [e for e in things if not e.seen]
    if unseen:
        lines.append("You know, not seen now:" if len(lines) < MAX_LINES - 1 else None)
        for e in unseen:
            lines.append(f"- {noun_phrase(snapshot, e)}{place_phrase(snapshot, e)}"
                         if len(lines) < MAX_LINES else None)
    kept: list[str] = []
    size = 0
    for line in lines:
        if line is None or len(kept) >= MAX_LINES or size + len(line) + 1 > MAX_CHARS:
            break
        kept.append(line)
        size += len(line) + 1
    return Description(tuple(kept), len(lines) - len(kept))


def _and(items: list[str]) -> str:
    if len(items) <= 1:
        return "".join(items)
    return ", ".join(items[:-1]) + " and " + items[-1]
