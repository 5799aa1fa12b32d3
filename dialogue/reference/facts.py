"""The facts a situation snapshot is made of, kept current from the KB's commits.

Loaded once with a few set-wide `find` queries, then updated from each commit's closure changes
(added and removed statements), so keeping them current costs what the commit changed, whatever the
size of the KB. Terms are in the KB's output form (`str(shorten(term))`), as `find` returns them.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any, Literal

from rdflib import BNode

from kb.protocol import KnowledgeBase
from kb.terms import shorten

ROBOT_ID = "myself"
PERSON_CLASSES = frozenset({"Human"})
ZONE_CLASSES = frozenset({"ZoneOfInterest"})

#: Situation properties -> the table each fills (an entity shows the first value by sorted text).
PROPERTIES = {
    "isOn": "support",
    "isIn": "zone",
    "hasColor": "colour",
    "belongsTo": "owner",
    "engagementLevel": "engagement",
    "isMovable": "movable",
}
#: Spatial relations beyond support and zone, with the preposition that says them in a reply; each
#: fills its own table (an entity shows all their values, relation by relation, by sorted text).
RELATIONS: tuple[tuple[str, str], ...] = (
    ("isNextTo", "next to"), ("cyc:near", "near"), ("isBelow", "under"), ("isAbove", "above"),
    ("behind", "behind"), ("inFrontOf", "in front of"), ("leftOf", "to the left of"),
    ("rightOf", "to the right of"),
)  # fmt: skip
#: What a person is to another in their family: the relations the language's kin words name.
Kin = Literal["child", "parent", "spouse", "sibling"]
#: Family relations, in the spellings scenes and ontologies use for them (ORO defines none), in one
#: table: each property -> what its object is to its subject and what its subject is to its object
#: ("ana isParentOf ben": ben is ana's child, ana is ben's parent).
KIN: dict[str, tuple[Kin, Kin]] = {
    "isParentOf": ("child", "parent"), "parentOf": ("child", "parent"), "hasChild": ("child", "parent"),
    "isChildOf": ("parent", "child"), "childOf": ("parent", "child"), "hasParent": ("parent", "child"),
    "isSpouseOf": ("spouse", "spouse"), "spouseOf": ("spouse", "spouse"), "hasSpouse": ("spouse", "spouse"),
    "isMarriedTo": ("spouse", "spouse"), "hasSibling": ("sibling", "sibling"),
    "isSiblingOf": ("sibling", "sibling"), "siblingOf": ("sibling", "sibling"),
}  # fmt: skip
#: Predicates whose change means an entity's classes or names must be asked again.
DEEP = frozenset({"rdf:type", "rdfs:label"})
#: Tables whose chosen value is a place, named in the snapshot's `names`.
PLACES = ("support", "zone")

Triple = tuple[Any, Any, Any]
#: Every property kept in a table, by the table's name (relations by their property).
_TABLES = {**PROPERTIES, **{prop: prop for prop, _prep in RELATIONS}, **{prop: prop for prop in KIN}}


@dataclass
class Change:
    """Terms a batch of statements touched: `deep` ones need their classes and labels asked again,
    `shallow` ones only their place, visibility or colour taken from the tables."""

    deep: set[str] = field(default_factory=set)
    shallow: set[str] = field(default_factory=set)
    #: Places that became or stopped being zones: what is in them is shown again.
    places: set[str] = field(default_factory=set)


class Facts:
    """Who the robot sees, who is a person or a place, and the situation properties per subject."""

    def __init__(self) -> None:
        self.seen: set[str] = set()
        self.people: set[str] = set()
        self.zones: set[str] = set()
        #: Terms with a label, and their labels: a thing the KB names is known even where nobody
        #: has seen or put it ("the diary", told of but never located).
        self.labelled: dict[str, set[str]] = {}
        self.tables: dict[str, dict[str, set[str]]] = {name: {} for name in _TABLES.values()}

    @classmethod
    def load(cls, kb: KnowledgeBase, labelled: list[dict[str, Any]] | None = None) -> Facts:
        """From the whole KB: the baseline the commits are applied to (and a full rebuild).
        ``labelled``: the rows of ``?x rdfs:label ?l`` when the caller has read them already."""
        facts = cls()
        facts.seen = {str(r["x"]) for r in kb.find(f"{ROBOT_ID} sees ?x")}
        facts.people = {str(r["x"]) for c in sorted(PERSON_CLASSES) for r in kb.find(f"?x rdf:type {c}")}
        facts.zones = {str(r["x"]) for c in sorted(ZONE_CLASSES) for r in kb.find(f"?x rdf:type {c}")}
        for row in kb.find("?x rdfs:label ?l") if labelled is None else labelled:
            facts.labelled.setdefault(str(row["x"]), set()).add(str(row["l"]))
        for prop, name in _TABLES.items():
            table = facts.tables[name]
            for row in kb.find(f"?x {prop} ?y"):
                table.setdefault(str(row["x"]), set()).add(str(row["y"]))
        return facts

    def value(self, table: str, term: str) -> str | None:
        """The value an entity shows: the first by sorted text, so the choice is deterministic; of
        the places a thing is in, a zone first (the ball in the toy box in the playroom: the
        playroom, the toy box is a container, in `relations`)."""
        values = self.tables[table].get(term)
        if not values:
            return None
        if table == "zone":
            zones = [v for v in values if v in self.zones]
            return min(zones) if zones else min(values)
        return min(values)

    def relations(self, term: str, zone: str | None) -> tuple[tuple[str, str], ...]:
        """The entity's other spatial facts: the other places it is in besides its zone (``zone``,
        its `value`) ("in": containers, the most specific places, before zones), then relation by
        relation, each by sorted text."""
        tables = self.tables
        placed = tables["zone"].get(term, ())
        inside: tuple[tuple[str, str], ...] = ()
        if len(placed) > 1:
            places = sorted(placed, key=lambda p: (p in self.zones, p))
            inside = tuple(("in", other) for other in places if other != zone)
        related = tuple((prep, other) for prop, prep in RELATIONS if term in tables[prop]
                        for other in sorted(tables[prop][term]))  # fmt: skip
        return inside + related if related else inside

    def kin(self, term: str) -> tuple[tuple[str, str], ...]:
        """The person's family as the KB relates it, either way round: (what they are to the person,
        who), by property, each by sorted text."""
        tables = self.tables
        forward = [(ahead, other) for prop, (ahead, _back) in KIN.items()
                   for other in tables[prop].get(term, ())]  # fmt: skip
        backward = [(back, subject) for prop, (_ahead, back) in KIN.items()
                    for subject, objects in tables[prop].items() if term in objects]  # fmt: skip
        return tuple(sorted(set(forward + backward)))

    def is_candidate(self, term: str) -> bool:
        """Worth considering as an entity: seen, a person, a place, located, named, or the robot.
        Of the named ones, schema terms and the ontology's values (colours, sizes, postures) are
        told apart by their classes (`entities`)."""
        return (
            term == ROBOT_ID
            or term in self.seen
            or term in self.people
            or term in self.zones
            or term in self.tables["support"]
            or term in self.tables["zone"]
            or term in self.labelled
        )

    def candidates(self) -> set[str]:
        located = (*self.tables["support"], *self.tables["zone"])
        return {ROBOT_ID, *self.seen, *self.people, *self.zones, *located, *self.labelled}

    def apply(self, added: Iterable[Triple], removed: Iterable[Triple], change: Change) -> None:
        """One commit's closure changes (removals first, as the writer applies them)."""
        for triples, present in ((removed, False), (added, True)):
            for s, p, o in triples:
                if isinstance(s, BNode) or isinstance(o, BNode):
                    continue  # never in `find` results
                self._apply(str(shorten(s)), str(shorten(p)), str(shorten(o)), present, change)

    def _apply(self, s: str, p: str, o: str, present: bool, change: Change) -> None:
        if p in DEEP:
            change.deep.add(s)
            if p == "rdfs:label":
                labels = self.labelled.setdefault(s, set())
                _set(labels, o, present)
                if not labels:
                    del self.labelled[s]
            if p == "rdf:type":
                for classes, members in ((PERSON_CLASSES, self.people), (ZONE_CLASSES, self.zones)):
                    if o in classes:
                        _set(members, s, present)
                if o in ZONE_CLASSES:  # what is in it now shows it as its zone or its container
                    change.places.add(s)
            return
        if p == "sees":
            if s == ROBOT_ID:
                _set(self.seen, o, present)
                change.shallow.add(o)
            return
        name = _TABLES.get(p)
        if name is None:
            return
        table = self.tables[name]
        values = table.setdefault(s, set())
        _set(values, o, present)
        if not values:
            del table[s]
        change.shallow.add(s)
        if p in KIN:  # (the object's family changed too)
            change.shallow.add(o)


def _set(members: set[str], term: str, present: bool) -> None:
    if present:
        members.add(term)
    else:
        members.discard(term)
