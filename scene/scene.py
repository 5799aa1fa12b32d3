"""A 2D scene (robot, people, objects, furniture, zones) and the facts it implies (scene-compat §3–6).

The facts are those the ROS4HRI interaction simulator computes — ``rdf:type``, ``rdfs:label``,
``sees`` for every agent (field-of-view sector), ``isIn`` zones and ``isOn`` supports by box
overlap and stacking order — kept as state: every change yields the exact difference to the
previous facts, so nothing stale is left when an entity moves, disappears or stops observing
(S1–S3). Only the relations an entity takes part in are recomputed when it changes.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field, replace
from enum import StrEnum
from typing import Literal

from rdflib import Literal as RdfLiteral

from kb.terms import format_term
from kb.unicode import check_carried, check_text
from scene.geometry import Box, Sector

ROBOT_ID = "myself"


class Kind(StrEnum):
    ROBOT = "robot"
    PERSON = "person"
    OBJECT = "object"
    FURNITURE = "furniture"
    ZONE = "zone"


AGENTS = frozenset({Kind.ROBOT, Kind.PERSON})
SUBJECTS = frozenset({Kind.OBJECT, Kind.FURNITURE})
DEFAULT_CLASS = {Kind.ROBOT: "Robot", Kind.PERSON: "Human", Kind.OBJECT: "Object",
                 Kind.FURNITURE: "Object", Kind.ZONE: "ZoneOfInterest"}
DEFAULT_SIZE = {Kind.ROBOT: 0.2, Kind.PERSON: 0.3, Kind.OBJECT: 0.2, Kind.FURNITURE: 1.0, Kind.ZONE: 1.0}
DEFAULT_Z = {Kind.ZONE: -100, Kind.FURNITURE: 0, Kind.OBJECT: 0, Kind.ROBOT: 10, Kind.PERSON: 10}


@dataclass(frozen=True)
class Entity:
    """One thing in the scene; position and heading in the robot's frame (metres, radians)."""

    id: str
    kind: Kind
    cls: str = ""
    label: str | None = None
    x: float = 0.0
    y: float = 0.0
    heading: float = 0.0
    width: float | None = None
    depth: float | None = None
    z: int | None = None

    def __post_init__(self) -> None:
        for name, text in (("id", self.id), ("class", self.cls), ("label", self.label)):
            if isinstance(text, str):
                check_text(text, f"the {name} of scene entity {self.id!r}")
                check_carried(text, f"the {name} of scene entity {self.id!r}")
        if not self.cls:
            object.__setattr__(self, "cls", DEFAULT_CLASS[self.kind])

    @property
    def box(self) -> Box:
        width = self.width if self.width is not None else DEFAULT_SIZE[self.kind]
        depth = self.depth if self.depth is not None else width
        return Box.around(self.x, self.y, width, depth, self.heading)

    @property
    def level(self) -> int:
        return self.z if self.z is not None else DEFAULT_Z[self.kind]


@dataclass(frozen=True)
class SceneConfig:
    """Policies where the simulator's behaviour is a choice (S5, S7, S8); defaults match it."""

    fov_degrees: float = 120.0  # total aperture of every agent's field of view
    range_m: float = 3.5
    agents_in_zones: bool = False  # S7: upstream never states `<agent> isIn <zone>`
    zones: Literal["all", "largest"] = "all"  # S8: an item straddling zones is in all of them
    supports: Literal["all", "top"] = "all"  # upstream: isOn every overlapping item below

    def sector(self, agent: Entity) -> Sector:
        return Sector(agent.x, agent.y, agent.heading, math.radians(self.fov_degrees) / 2, self.range_m)


@dataclass
class Diff:
    """Statements to add and to retract, in the KB's statement syntax."""

    added: set[str] = field(default_factory=set)
    removed: set[str] = field(default_factory=set)

    def __bool__(self) -> bool:
        return bool(self.added or self.removed)

    def as_dict(self) -> dict[str, list[str]]:
        return {"added": sorted(self.added), "removed": sorted(self.removed)}


class Scene:
    """The entities and the facts they imply, maintained incrementally."""

    def __init__(self, config: SceneConfig | None = None) -> None:
        self.config = config or SceneConfig()
        robot = Entity(ROBOT_ID, Kind.ROBOT)
        self._entities: dict[str, Entity] = {ROBOT_ID: robot}
        self._boxes: dict[str, Box] = {ROBOT_ID: robot.box}
        self._order: dict[str, int] = {ROBOT_ID: 0}
        self._next = 1
        self._own: dict[str, frozenset[str]] = {}  # type and label of each entity
        self._sees: dict[str, set[str]] = {}  # observer -> ids it sees
        self._spatial: dict[str, frozenset[str]] = {}  # statements with the entity as subject
        self._extra: dict[str, frozenset[str]] = {}  # per-entity facts set by others (engagement)
        self._refresh_all()

    # --- reading ---------------------------------------------------------------------------

    def __contains__(self, entity_id: str) -> bool:
        return entity_id in self._entities

    def __iter__(self) -> Iterator[Entity]:
        return iter(self._entities.values())

    def get(self, entity_id: str) -> Entity | None:
        return self._entities.get(entity_id)

    def facts(self) -> set[str]:
        out: set[str] = set()
        for part in (self._own, self._spatial, self._extra):
            for statements in part.values():
                out |= statements
        for observer, seen in self._sees.items():
            out |= {f"{observer} sees {target}" for target in seen}
        return out

    # --- changing --------------------------------------------------------------------------

    def put(self, entity: Entity) -> Diff:
        """Create or move an entity; return the change of facts."""
        if entity.kind is Kind.ROBOT and entity.id != ROBOT_ID:
            raise ValueError(f"the robot is {ROBOT_ID!r}; {entity.id!r} cannot be a robot")
        before = self.facts()
        old = self._boxes.get(entity.id)
        self._entities[entity.id] = entity
        self._boxes[entity.id] = entity.box
        if entity.id not in self._order:
            self._order[entity.id] = self._next
            self._next += 1
        self._refresh_around(entity, old)
        return _diff(before, self.facts())

    def remove(self, entity_id: str) -> Diff:
        """Remove an entity and every fact about it (S1)."""
        if entity_id == ROBOT_ID:
            raise ValueError("the robot cannot be removed from the scene")
        if entity_id not in self._entities:
            raise KeyError(entity_id)
        before = self.facts()
        del self._entities[entity_id]
        old = self._boxes.pop(entity_id)
        self._order.pop(entity_id)
        self._own.pop(entity_id, None)
        self._sees.pop(entity_id, None)
        self._spatial.pop(entity_id, None)
        self._extra.pop(entity_id, None)
        for seen in self._sees.values():
            seen.discard(entity_id)
        for other in self._overlapping(old):
            self._spatial[other.id] = self._relations(other)
        return _diff(before, self.facts())

    def set_extra(self, entity_id: str, statements: Iterable[str]) -> Diff:
        """Facts about an entity computed elsewhere (its engagement level), kept in sync too."""
        before = self.facts()
        if entity_id in self._entities:
            self._extra[entity_id] = frozenset(statements)
        return _diff(before, self.facts())

    def reconfigure(self, config: SceneConfig) -> Diff:
        before = self.facts()
        self.config = config
        self._refresh_all()
        return _diff(before, self.facts())

    # --- computing -------------------------------------------------------------------------

    def _refresh_all(self) -> None:
        self._own = {e.id: _own_facts(e) for e in self._entities.values()}
        self._sees = {e.id: self._seen_by(e) for e in self._entities.values() if e.kind in AGENTS}
        self._spatial = {e.id: self._relations(e) for e in self._entities.values()}

    def _refresh_around(self, entity: Entity, old: Box | None) -> None:
        self._own[entity.id] = _own_facts(entity)
        if entity.kind in AGENTS:
            self._sees[entity.id] = self._seen_by(entity)
        else:
            self._sees.pop(entity.id, None)
        for observer_id in self._sees:
            if observer_id == entity.id:
                continue
            observer = self._entities[observer_id]
            seen = self._sees[observer_id]
            if self.config.sector(observer).intersects(self._boxes[entity.id]):
                seen.add(entity.id)
            else:
                seen.discard(entity.id)
        affected = {entity.id} | {e.id for e in self._overlapping(self._boxes[entity.id])}
        if old is not None:
            affected |= {e.id for e in self._overlapping(old)}
        for entity_id in affected:
            self._spatial[entity_id] = self._relations(self._entities[entity_id])

    def _seen_by(self, observer: Entity) -> set[str]:
        sector = self.config.sector(observer)
        boxes = self._boxes
        return {e for e in self._entities if e != observer.id and sector.intersects(boxes[e])}

    def _overlapping(self, box: Box) -> Iterator[Entity]:
        boxes = self._boxes
        return (e for e in self._entities.values() if boxes[e.id].overlaps(box))

    def _stack(self, entity: Entity) -> tuple[int, int]:
        # Higher z is above; with equal z the entity inserted later is above (§2.5).
        return (entity.level, self._order[entity.id])

    def _relations(self, subject: Entity) -> frozenset[str]:
        """``S isOn X`` for items X below S, ``S isIn Z`` for zones Z, per the policies (§5)."""
        if subject.kind is Kind.ZONE:
            return frozenset()
        agent = subject.kind in AGENTS
        boxes = self._boxes
        box, level = boxes[subject.id], self._stack(subject)
        supports: list[Entity] = []
        zones: list[Entity] = []
        for other in self._entities.values():
            if other.id == subject.id or not boxes[other.id].overlaps(box):
                continue
            if other.kind is Kind.ZONE:
                zones.append(other)
            elif self._stack(other) < level:
                supports.append(other)
        if self.config.supports == "top" and supports:
            supports = [max(supports, key=self._stack)]
        if agent and not self.config.agents_in_zones:
            zones = []
        if self.config.zones == "largest" and zones:
            zones = [max(zones, key=lambda z: (boxes[z.id].overlap_area(box), z.id))]
        return frozenset(
            [f"{subject.id} isOn {s.id}" for s in supports] + [f"{subject.id} isIn {z.id}" for z in zones]
        )


def moved(entity: Entity, x: float, y: float, heading: float | None = None) -> Entity:
    return replace(entity, x=x, y=y, heading=entity.heading if heading is None else heading)


def _own_facts(entity: Entity) -> frozenset[str]:
    facts = {f"{entity.id} rdf:type {entity.cls}"}
    if entity.label:
        facts.add(f"{entity.id} rdfs:label {format_term(RdfLiteral(entity.label))}")
    return frozenset(facts)


def _diff(before: set[str], after: set[str]) -> Diff:
    return Diff(added=after - before, removed=before - after)
