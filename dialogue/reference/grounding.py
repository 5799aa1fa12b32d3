"""The situation snapshot: what the KB knows that a dialogue turn may refer to.

A snapshot is built from a handful of `find` queries and cached per KB revision, so a turn on an
unchanged KB costs a dictionary lookup. Entities are ordered deterministically: the robot's visible
things first, then people, places and other located things, each group sorted by id.
"""

from __future__ import annotations

import re
import threading
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any, Literal

from rdflib import Literal as RdfLiteral

from kb import KbError
from kb.protocol import KnowledgeBase
from kb.terms import shorten

Kind = Literal["person", "zone", "robot", "thing"]

ROBOT_ID = "myself"
PERSON_CLASSES = frozenset({"Human"})
ZONE_CLASSES = frozenset({"ZoneOfInterest"})
ROBOT_CLASSES = frozenset({"Robot"})

#: Types that make a term part of the vocabulary rather than the situation.
_SCHEMA_TYPES = frozenset(
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
_IGNORED_CLASSES = frozenset(
    {"owl:Thing", "rdfs:Resource", "owl:NamedIndividual", "ActiveConcept", "owl:Nothing"}
)


@dataclass(frozen=True)
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


@dataclass(frozen=True)
class Snapshot:
    """The situation at one KB revision. `entities` preserves the deterministic order."""

    revision: int
    entities: Mapping[str, Entity]
    robot: str = ROBOT_ID
    names: Mapping[str, str] = field(default_factory=dict)
    #: Terms considered and found not to be entities (schema terms, literals used as places).
    skipped: frozenset[str] = frozenset()

    def get(self, entity_id: str) -> Entity | None:
        return self.entities.get(entity_id)

    def name_of(self, term: str) -> str:
        """Readable name of any term (entity, class or value): its label, else a readable id."""
        entity = self.entities.get(term)
        if entity is not None:
            return entity.name
        return self.names.get(term) or readable_id(term)

    def of_kind(self, *kinds: Kind) -> list[Entity]:
        return [e for e in self.entities.values() if e.kind in kinds]

    def visible(self) -> list[Entity]:
        return [e for e in self.entities.values() if e.seen]


_CAMEL = re.compile(r"(?<=[a-z0-9])(?=[A-Z])")
_QUALIFIER = re.compile(r"_\([^)]*\)$")


def readable_id(term: str) -> str:
    """`dbr:Table_(furniture)` -> "table", `ZoneOfInterest` -> "zone of interest", `cup_1` -> "cup 1"."""
    local = term.rsplit("#", 1)[-1].rsplit("/", 1)[-1]
    local = local.split(":", 1)[-1] if ":" in local and not local.startswith("http") else local
    local = _QUALIFIER.sub("", local)
    local = _CAMEL.sub(" ", local).replace("_", " ").replace("-", " ")
    return " ".join(local.lower().split())


#: Past this many changed terms between two turns, a full rebuild is cheaper than bookkeeping.
MAX_DIRTY = 2000


class Grounder:
    """Builds snapshots from a KB and caches the last one per revision (thread-safe).

    With a KB that reports its commits (``kb.KB.on_commit``), the grounder records which terms
    changed; the next snapshot rebuilds only those entities and reuses the others, so perception
    writes between turns cost a turn little (a full rebuild asks the KB a few hundred questions).
    """

    def __init__(self, max_entities: int = 300, lang: str = "en") -> None:
        self.max_entities = max_entities
        self.lang = lang
        self._lock = threading.Lock()
        self._cached: Snapshot | None = None
        self._watched: object | None = None
        self._unwatch: Callable[[], None] | None = None
        self._dirty: set[str] | None = None  # None: unknown, rebuild everything

    def cached(self, revision: int) -> Snapshot | None:
        """The cached snapshot if it is still current (cheap: callable on an event loop)."""
        with self._lock:
            cached = self._cached
        return cached if cached is not None and cached.revision == revision else None

    def snapshot(self, kb: KnowledgeBase) -> Snapshot:
        cached = self.cached(kb.revision)
        if cached is not None:
            return cached
        with self._lock:
            if self._watched is not kb:
                self._watch(kb)
            dirty, self._dirty = self._dirty, (set() if self._unwatch is not None else None)
            previous = self._cached if dirty is not None else None
        snap = build_snapshot(kb, max_entities=self.max_entities, lang=self.lang,
                              previous=previous, dirty=dirty)
        with self._lock:
            self._cached = snap
        return snap

    def close(self) -> None:
        with self._lock:
            if self._unwatch is not None:
                self._unwatch()
            self._unwatch, self._watched, self._dirty = None, None, None

    def _watch(self, kb: KnowledgeBase) -> None:
        if self._unwatch is not None:
            self._unwatch()
        self._watched, self._unwatch, self._dirty, self._cached = kb, None, None, None
        on_commit = getattr(kb, "on_commit", None)
        if callable(on_commit):
            self._unwatch = on_commit(self._changed)

    def _changed(self, commit: Any) -> None:
        """Called by the KB under its lock with every commit: note the terms it touched."""
        with self._lock:
            if self._dirty is None:
                return
            if getattr(commit, "cleared", None) is not None:
                self._dirty = None
                return
            for delta in commit.deltas:
                if delta.model != "default":
                    continue
                for s, _p, o in (*delta.added, *delta.removed):
                    self._dirty.add(str(shorten(s)))
                    if not isinstance(o, RdfLiteral):
                        self._dirty.add(str(shorten(o)))
            if len(self._dirty) > MAX_DIRTY:
                self._dirty = None


def _pattern_term(term: str) -> str:
    """A term as the KB printed it, made usable in a pattern again (full IRIs need angle brackets)."""
    return f"<{term}>" if "://" in term else term


#: Spatial relations beyond support and zone, with the preposition that says them in a reply.
RELATIONS: tuple[tuple[str, str], ...] = (
    ("isNextTo", "next to"), ("cyc:near", "near"), ("isBelow", "under"), ("isAbove", "above"),
    ("behind", "behind"), ("inFrontOf", "in front of"),
)  # fmt: skip


def build_snapshot(kb: KnowledgeBase, max_entities: int = 300, lang: str = "en",
                   previous: Snapshot | None = None, dirty: set[str] | None = None) -> Snapshot:
    """A few set-wide queries, then small per-entity ones: cheap even with many visible objects.

    With the ``previous`` snapshot and the terms that changed since (``dirty``), entities whose
    own facts did not change are reused, only their place and visibility refreshed."""
    revision = kb.revision
    if previous is not None and dirty is not None and _classes_changed(previous, dirty):
        previous = None  # a class's label changed: the names of many entities may have
    seen = {str(r["x"]) for r in kb.find(f"{ROBOT_ID} sees ?x")}
    people = {str(r["x"]) for c in PERSON_CLASSES for r in kb.find(f"?x rdf:type {c}")}
    zones = {str(r["x"]) for c in ZONE_CLASSES for r in kb.find(f"?x rdf:type {c}")}
    support = _single(kb.find("?x isOn ?y"))
    zone = _single(kb.find("?x isIn ?y"))
    colour = _single(kb.find("?x hasColor ?y"))
    owner = _single(kb.find("?x belongsTo ?y"))
    engagement = _single(kb.find("?x engagementLevel ?y"))
    relations: dict[str, list[tuple[str, str]]] = {}
    for prop, prep in RELATIONS:
        for row in sorted(kb.find(f"?x {prop} ?y"), key=lambda r: (str(r["x"]), str(r["y"]))):
            relations.setdefault(str(row["x"]), []).append((prep, str(row["y"])))

    def rank(term: str) -> int:
        if term in seen:
            return 0
        if term in people:
            return 1
        return 2 if term in zones else 3

    # Unseen things count only when located (or people, places, the robot): labelled but unplaced
    # individuals are mostly the ontology's own (colours, sizes, postures).
    terms = seen | people | zones | set(support) | set(zone) | {ROBOT_ID}
    candidates = sorted((rank(t), t) for t in terms)

    labels: dict[str, list[str]] = {}
    display: dict[str, str] = {}
    reusable = _reusable(previous, dirty)
    # Instance labels in a few joins rather than one query per entity (the per-query cost dominates);
    # not needed when most entities are reused.
    for pattern in () if reusable else (
        f"{ROBOT_ID} sees ?x",
        "?x isIn ?y",
        "?x isOn ?y",
        *(f"?x rdf:type {c}" for c in (*PERSON_CLASSES, *ZONE_CLASSES)),
    ):
        for row in kb.find([pattern, "?x rdfs:label ?l"]):
            values = labels.setdefault(str(row["x"]), [])
            if isinstance(row["l"], str) and row["l"] not in values:
                values.append(row["l"])
    for term in () if reusable else terms - labels.keys():
        if term in seen or term in people or term in zones or term in support or term in zone:
            labels[term] = []  # covered by the joins above: no label

    def labels_of(term: str) -> list[str]:
        if term not in labels:
            found = kb.find(f"{_pattern_term(term)} rdfs:label ?l")
            labels[term] = list(dict.fromkeys(str(r["l"]) for r in found if isinstance(r["l"], str)))
        return labels[term]

    def display_name(term: str) -> str:
        # The label in the wanted language first (D17); other languages still match in the lexicon.
        if term not in display:
            display[term] = kb.label(term, lang) if labels_of(term) else readable_id(term)
        return display[term]

    per_class: dict[tuple[str, bool], tuple[str, ...]] = {}
    skipped: set[str] = set()

    def class_words(klass: str, asserted: bool) -> tuple[str, ...]:
        # An unlabelled asserted class still names its instances ("Remote" -> "remote"); unlabelled
        # inferred superclasses (cyc:SpatialThing...) would only add noise.
        key = (klass, asserted)
        if key not in per_class:
            found = labels_of(klass)
            names = [display_name(klass), *found] if found or asserted else []
            per_class[key] = tuple(dict.fromkeys(n.lower() for n in names))
        return per_class[key]

    entities: dict[str, Entity] = {}
    for _rank, term in candidates:
        if len(entities) >= max_entities:
            break
        old = reusable.get(term)
        if old is not None:
            hue = colour.get(term)
            entities[term] = replace(
                old, seen=term in seen, support=support.get(term), zone=zone.get(term),
                colour=display_name(hue) if hue else None, engagement=engagement.get(term),
                owner=owner.get(term), relations=tuple(relations.get(term, ())),
            )
            continue
        if previous is not None and dirty is not None and term in previous.skipped and term not in dirty:
            skipped.add(term)  # not an entity last time, and nothing about it changed
            continue
        try:
            all_classes = kb.classesof(term)
            labels_of(term)
        except KbError:
            continue  # a literal used as a place ("x isIn 'garden'") is not an entity
        if set(all_classes) & _SCHEMA_TYPES or (not all_classes and term not in seen):
            skipped.add(term)
            continue
        direct = [c for c in kb.classesof(term, direct=True) if c not in _IGNORED_CLASSES]
        inferred = sorted(c for c in all_classes if c not in _IGNORED_CLASSES and c not in direct)
        class_names = tuple(
            dict.fromkeys(name for c in (*direct, *inferred) for name in class_words(c, asserted=c in direct))
        )
        own_labels = tuple(dict.fromkeys([display_name(term), *labels_of(term)])) if labels_of(term) else ()
        klass = set(all_classes)
        kind: Kind
        if term == ROBOT_ID or klass & ROBOT_CLASSES:
            kind = "robot"
        elif klass & PERSON_CLASSES:
            kind = "person"
        elif klass & ZONE_CLASSES:
            kind = "zone"
        else:
            kind = "thing"
        name = own_labels[0] if own_labels else (class_names[0] if class_names else readable_id(term))
        hue = colour.get(term)
        entities[term] = Entity(
            id=term, name=name, labels=own_labels, classes=(*direct, *inferred),
            class_names=class_names, kind=kind, seen=term in seen, support=support.get(term),
            zone=zone.get(term), colour=display_name(hue) if hue else None,
            engagement=engagement.get(term), owner=owner.get(term),
            relations=tuple(relations.get(term, ())),
        )  # fmt: skip
    others = {other for found in relations.values() for _prep, other in found}
    names = {term: display_name(term) for term in {*support.values(), *zone.values(), *others}}
    return Snapshot(revision=revision, entities=entities, names=names, skipped=frozenset(skipped))


def _classes_changed(previous: Snapshot, dirty: set[str]) -> bool:
    return any(c in dirty for e in previous.entities.values() for c in e.classes)


def _reusable(previous: Snapshot | None, dirty: set[str] | None) -> dict[str, Entity]:
    if previous is None or dirty is None:
        return {}
    return {term: e for term, e in previous.entities.items() if term not in dirty}


def _single(rows: list[dict[str, Any]]) -> dict[str, str]:
    """First value per subject, in sorted order so that the choice is deterministic."""
    out: dict[str, str] = {}
    for row in sorted(rows, key=lambda r: (str(r["x"]), str(r["y"]))):
        out.setdefault(str(row["x"]), str(row["y"]))
    return out
