"""The situation snapshot: every entity the KB knows that a dialogue turn may refer to.

A snapshot is immutable: one per KB revision, shared by every turn at that revision. Entities are
ordered deterministically: the robot's visible things first, then people, places and other located
things, each group sorted by id (`EntityTable` keeps that order without sorting per revision).
"""

from __future__ import annotations

import re
from collections.abc import Collection, Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from itertools import islice
from typing import Any, Literal

from dialogue.reference.facts import ROBOT_ID
from dialogue.reference.layered import SortedChunks

Kind = Literal["person", "zone", "robot", "thing"]

ROBOT_CLASSES = frozenset({"Robot"})

#: Types that make a term part of the vocabulary rather than the situation.
SCHEMA_TYPES = frozenset(
    {
        "owl:Class",
        "rdfs:Class",
        "owl:ObjectProperty",
        "owl:DatatypeProperty",
        "owl:AnnotationProperty",
        "rdf:Property",
        "owl:TransitiveProperty",
        "owl:SymmetricProperty",
        "owl:FunctionalProperty",
        "owl:InverseFunctionalProperty",
        "owl:Ontology",
        "owl:Restriction",
        "rdfs:Datatype",
        "owl:AsymmetricProperty",
        "owl:IrreflexiveProperty",
        "owl:ReflexiveProperty",
    }
)
#: Classes too generic to name anything in speech.
IGNORED_CLASSES = frozenset(
    {"owl:Thing", "rdfs:Resource", "owl:NamedIndividual", "ActiveConcept", "owl:Nothing"}
)
#: Classes whose members are values said of things (a colour, a size, a posture), never things a
#: person talks about: the ontology names them, and a named term of these classes is no entity.
VALUE_CLASSES = frozenset(
    {"cyc:Color", "Size", "Shape", "Posture", "EngagementLevel", "Situation", "cyc:Situation"}
)

#: The ontology's value for a place nobody knows ("isIn unknownLocation"): no thing of its own.
VALUE_TERMS = frozenset({"unknownLocation"})


@dataclass(frozen=True, slots=True)
class Entity:
    """One individual the dialogue may refer to. `id` is what intents carry (D17)."""

    id: str
    name: str
    labels: tuple[str, ...]
    classes: tuple[str, ...]
    class_names: tuple[str, ...]
    kind: Kind
    seen: bool
    support: str | None = None
    zone: str | None = None
    colour: str | None = None
    #: Whose it is (`belongsTo`): lets "my phone" and "Ines's phone" tell two phones apart.
    owner: str | None = None
    #: A person's engagement with the robot (`engaging`, `engaged`, `disengaging`, `disengaged`).
    engagement: str | None = None
    #: Other spatial facts, as (preposition, entity id): ("next to", "bed_1") for `isNextTo`.
    relations: tuple[tuple[str, str], ...] = ()
    #: Whether it can be picked up and carried (`isMovable`); None when the KB does not say.
    movable: bool | None = None
    #: A person's family as the KB relates it (`facts.KIN`): (what they are to this person, who).
    kin: tuple[tuple[str, str], ...] = ()


#: The ontology's class of furniture: it stays where it is unless the KB says it can be moved.
FURNITURE = "cyc:FurniturePiece"


def fixed(entity: Entity) -> bool:
    """Whether the thing cannot be picked up or carried: the KB says it is not movable, or it is
    furniture the KB does not say is (people and places are never carried as objects anyway)."""
    if entity.movable is not None:
        return not entity.movable
    return FURNITURE in entity.classes


#: Ranks of the deterministic order: seen by the robot, people, places, other located things.
SEEN, PERSON, ZONE, OTHER = range(4)


def rank(entity: Entity) -> int:
    """Where an entity comes in the deterministic order (its classes include the inferred ones)."""
    if entity.seen:
        return SEEN
    if "Human" in entity.classes:
        return PERSON
    return ZONE if "ZoneOfInterest" in entity.classes else OTHER


class EntityTable(Mapping[str, Entity]):
    """An immutable view of the entities at one revision, iterated in rank-then-id order.

    Built from a version of the maintained entities and their sorted order, both shared with the
    other versions (no sorting, no copy), so a revision costs little more than what changed."""

    __slots__ = ("_by_id", "_order")

    def __init__(self, by_id: Mapping[str, Entity], order: SortedChunks[tuple[int, str]]) -> None:
        self._by_id = by_id
        self._order = order

    def __getitem__(self, key: str) -> Entity:
        return self._by_id[key]

    def get(self, key: str, default: Any = None) -> Any:
        return self._by_id.get(key, default)

    def __contains__(self, key: object) -> bool:
        return key in self._by_id

    def __len__(self) -> int:
        return len(self._by_id)

    def __iter__(self) -> Iterator[str]:
        return (term for _rank, term in self._order)

    def ranked_up_to(self, rank: int) -> Iterator[Entity]:
        """The entities of the first ranks only (cheap: visible things, people, places)."""
        return (self._by_id[term] for _rank, term in self._order.before((rank + 1, "")))


@dataclass(frozen=True)
class Snapshot:
    """The situation at one KB revision. `entities` preserves the deterministic order."""

    revision: int
    entities: Mapping[str, Entity]
    robot: str = ROBOT_ID
    names: Mapping[str, str] = field(default_factory=dict)
    #: Terms considered and found not to be entities (schema terms, unseen untyped terms).
    skipped: frozenset[str] = frozenset()
    #: The last few steps that led to this snapshot, oldest first: (revision of an earlier snapshot,
    #: ids of the entities that changed from it to the next). Lets a lexicon of any of those
    #: revisions be updated rather than rebuilt. Empty: built from scratch.
    changed: tuple[tuple[int, frozenset[str]], ...] = field(default=(), compare=False)
    #: Place id -> ids of the entities whose support or zone it is ("what is on the shelf"
    #: without looking at every entity), each a set as a mapping to None (layered once large: a
    #: zone's is shared with the previous snapshot's). None: not kept (a snapshot made by hand).
    contents: Mapping[str, Mapping[str, None]] | None = None

    def changed_since(self, revision: int) -> frozenset[str] | None:
        """Ids of the entities that changed since the snapshot at `revision`; None if unknown."""
        for n, (base, _ids) in enumerate(self.changed):
            if base == revision:
                return frozenset().union(*(ids for _base, ids in self.changed[n:]))
        return None

    def get(self, entity_id: str) -> Entity | None:
        return self.entities.get(entity_id)

    def name_of(self, term: str) -> str:
        """Readable name of any term (entity, class or value): its label, else a readable id."""
        entity = self.entities.get(term)
        if entity is not None:
            return entity.name
        return self.names.get(term) or readable_id(term)

    def robot_name(self, default: str) -> str:
        """The robot's own name, its label in the KB ("Pip"); `default` when it has none but its id."""
        robot = self.entities.get(self.robot)
        return robot.name if robot is not None and robot.name != robot.id else default

    def order_key(self, entity_id: str) -> tuple[int, str]:
        """Sort key of the deterministic order (unknown ids last)."""
        entity = self.entities.get(entity_id)
        return (rank(entity) if entity is not None else OTHER + 1, entity_id)

    def in_order(self, entities: Iterable[Entity]) -> list[Entity]:
        return sorted(entities, key=lambda e: self.order_key(e.id))

    def of_kind(self, *kinds: Kind) -> list[Entity]:
        # People and places rank at most ZONE; things and the robot may rank OTHER.
        last = ZONE if set(kinds) <= {"person", "zone"} else OTHER
        return [e for e in self._first(last) if e.kind in kinds]

    def placed_at(self, place: str) -> list[Entity]:
        """The entities on or in ``place`` (support, zone or container), in the deterministic order
        (with a zone a thing is also in, that the caller tells apart)."""
        if self.contents is None:
            return [e for e in self.entities.values()
                    if place in (e.support, e.zone) or ("in", place) in e.relations]  # fmt: skip
        return self.in_order(self.entities[i] for i in self.contents.get(place, ()) if i in self.entities)

    def first_of_kind(self, kinds: Collection[Kind], n: int) -> list[Entity]:
        """The first ``n`` entities of these kinds in the deterministic order (what the robot
        sees, people, places first): people and places are found without walking the things."""
        last = ZONE if set(kinds) <= {"person", "zone"} else OTHER
        return list(islice((e for e in self._first(last) if e.kind in kinds), n))

    def among(self, ids: Collection[str], kinds: Collection[Kind]) -> list[Entity]:
        """The entities of ``ids`` of these kinds, unordered. People and places are found among
        the people and places when ``ids`` are many (a class word names thousands of things)."""
        if len(ids) > _MANY_IDS and set(kinds) <= {"person", "zone"}:
            return [e for e in self.of_kind(*kinds) if e.id in ids]
        return [e for i in ids if (e := self.entities.get(i)) is not None and e.kind in kinds]

    def seen_among(self, ids: Collection[str]) -> list[Entity]:
        """The seen entities of ``ids``, unordered: found among the visible ones when ``ids`` are
        many (a class word names thousands of things, a handful of them in sight)."""
        if len(ids) > _MANY_IDS:
            return [e for e in self.visible() if e.id in ids]
        return [e for i in ids if (e := self.entities.get(i)) is not None and e.seen]

    def visible(self) -> list[Entity]:
        return [e for e in self._first(SEEN) if e.seen]

    def _first(self, rank: int) -> Iterator[Entity]:
        """Entities up to a rank; people and places never rank below ZONE, seen things at SEEN."""
        if isinstance(self.entities, EntityTable):
            return self.entities.ranked_up_to(rank)
        return iter(self.entities.values())


#: Past this many ids, `Snapshot.among` walks the people and places, and `seen_among` the visible
#: entities, rather than the ids.
_MANY_IDS = 64

_CAMEL = re.compile(r"(?<=[a-z0-9])(?=[A-Z])")
_QUALIFIER = re.compile(r"_\([^)]*\)$")


def readable_id(term: str) -> str:
    """`dbr:Table_(furniture)` -> "table", `ZoneOfInterest` -> "zone of interest", `cup_1` -> "cup 1"."""
    local = term.rsplit("#", 1)[-1].rsplit("/", 1)[-1]
    local = local.split(":", 1)[-1] if ":" in local and not local.startswith("http") else local
    local = _QUALIFIER.sub("", local)
    local = _CAMEL.sub(" ", local).replace("_", " ").replace("-", " ")
    return " ".join(local.lower().split())


