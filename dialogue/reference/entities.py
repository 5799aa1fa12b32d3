"""The entities of the situation, maintained from what each commit changed.

`EntityIndex` holds the mutable state behind the snapshots: the facts (`facts.Facts`), each
candidate's classes and names (asked of the KB once, again only when its types or labels change),
display names per term, and the entities in their deterministic order (a sorted list kept with
`bisect`). A commit touching N statements costs O(N) KB questions and updates; `freeze` copies the
state into an immutable `Snapshot` (the entities as a `layered.Layered` version of the last
snapshot's, the order as a flat copy: no sorting and no KB access).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass

from dialogue.reference.facts import PERSON_CLASSES, PLACES, ROBOT_ID, ZONE_CLASSES, Change, Facts, Triple
from dialogue.reference.layered import GONE, Layered, SortedChunks
from dialogue.reference.snapshot import (
    IGNORED_CLASSES,
    ROBOT_CLASSES,
    SCHEMA_TYPES,
    Entity,
    EntityTable,
    Kind,
    Snapshot,
    rank,
    readable_id,
)
from kb import KbError
from kb.protocol import KnowledgeBase

#: Kind of an entity by its classes, first match wins (the robot also by its id).
_KINDS: tuple[tuple[frozenset[str], Kind], ...] = (
    (ROBOT_CLASSES, "robot"),
    (PERSON_CLASSES, "person"),
    (ZONE_CLASSES, "zone"),
)


@dataclass(frozen=True)
class _Core:
    """What the KB says of a term itself (asked again only when its types or labels change)."""

    labels: tuple[str, ...]
    classes: tuple[str, ...]
    class_names: tuple[str, ...]
    kind: Kind
    name: str
    #: A schema term (class, property...): never an entity.
    schema: bool
    #: Has any class: an unseen untyped term is no entity either.
    typed: bool


class EntityIndex:
    """Mutable; used by one thread at a time (the grounder serialises its builds)."""

    def __init__(self, kb: KnowledgeBase, lang: str = "en") -> None:
        self.kb = kb
        self.lang = lang
        self.facts = Facts.load(kb)
        self._cores: dict[str, _Core | None] = {}  # None: not a term the KB can describe
        self._labels: dict[str, tuple[str, ...]] = {}
        self._display: dict[str, str] = {}
        self._class_words: dict[tuple[str, bool], tuple[str, ...]] = {}
        self._users: dict[str, set[str]] = {}  # class -> terms whose core uses its words
        self._hue_users: dict[str, set[str]] = {}  # colour value -> entities showing its name
        self._hue: dict[str, str] = {}
        self._placed: dict[str, tuple[str | None, ...]] = {}  # subject -> its shown support, zone
        self._refs: Counter[str] = Counter()
        self.names: dict[str, str] = {}
        self.entities: dict[str, Entity] = {}
        self._frozen: Layered[str, Entity] | None = None  # the last snapshot's entities
        self._touched: set[str] = set()  # entities changed since
        self._contents: dict[str, set[str]] = {}  # place -> entities on it or in it
        self._located: dict[str, tuple[str | None, ...]] = {}  # entity -> (support, zone, *containers)
        self._frozen_contents: Layered[str, frozenset[str]] | None = None
        self._moved: set[str] = set()  # places whose contents changed since the last snapshot
        self._rank: dict[str, int] = {}
        #: (rank, id) of every entity, sorted; shared by the snapshots it did not change in.
        self.order: SortedChunks[tuple[int, str]] | None = None  # None: built at the end of __init__
        self.skipped: set[str] = set()
        self._prefetch_labels()
        for term in sorted(self.facts.candidates()):
            self.update(term)
        self.order = SortedChunks((rank, term) for term, rank in self._rank.items())

    def _prefetch_labels(self) -> None:
        # One join per candidate group instead of one query per entity (the per-query cost dominates).
        for pattern in (f"{ROBOT_ID} sees ?x", "?x isIn ?y", "?x isOn ?y",
                        *(f"?x rdf:type {c}" for c in sorted(PERSON_CLASSES | ZONE_CLASSES))):
            for row in self.kb.find([pattern, "?x rdfs:label ?l"]):
                values = self._labels.setdefault(str(row["x"]), ())
                if isinstance(row["l"], str) and row["l"] not in values:
                    self._labels[str(row["x"])] = (*values, row["l"])
        for term in self.facts.candidates() - {ROBOT_ID}:  # covered by the joins: no label
            self._labels.setdefault(term, ())

    def apply(self, added: Iterable[Triple], removed: Iterable[Triple]) -> set[str]:
        """One commit's closure changes; returns the terms whose entity may have changed."""
        change = Change()
        self.facts.apply(added, removed, change)
        return self.refresh(change)

    def refresh(self, change: Change) -> set[str]:
        deep = set(change.deep)
        shallow = set(change.shallow)
        for place in change.places:
            shallow |= self._contents.get(place, set())
        for term in change.deep:
            self._forget(term)
            # Its name shows in others: its instances' class names, a colour's users, places.
            for asserted in (True, False):
                self._class_words.pop((term, asserted), None)
            deep |= self._users.get(term, set())
            shallow |= self._hue_users.get(term, set())
            if term in self.names:
                self.names[term] = self.display(term)
        for term in deep:
            self._cores.pop(term, None)
        for term in deep | shallow:
            self.update(term)
        return deep | shallow

    def _forget(self, term: str) -> None:
        self._labels.pop(term, None)
        self._display.pop(term, None)

    def update(self, term: str) -> None:
        """Recompute one term's entity from the facts and its (cached) core."""
        self._place(term)
        core = self._core(term) if self.facts.is_candidate(term) else None
        seen = term in self.facts.seen
        if core is None or core.schema or (not core.typed and not seen):
            self._drop(term)
            if core is not None:
                self.skipped.add(term)
            return
        self.skipped.discard(term)
        hue = self.facts.value("colour", term)
        self._set_hue(term, hue)
        self._touched.add(term)
        self.entities[term] = Entity(
            id=term, name=core.name, labels=core.labels, classes=core.classes,
            class_names=core.class_names, kind=core.kind, seen=seen,
            support=self.facts.value("support", term), zone=self.facts.value("zone", term),
            colour=self.display(hue) if hue else None,
            engagement=self.facts.value("engagement", term), owner=self.facts.value("owner", term),
            relations=self.facts.relations(term),
        )  # fmt: skip
        self._reorder(term, rank(self.entities[term]))
        entity = self.entities[term]
        inside = tuple(other for prep, other in entity.relations if prep == "in")
        self._locate(term, (entity.support, entity.zone, *inside))

    def freeze(self, revision: int, changed: tuple[tuple[int, frozenset[str]], ...] = ()) -> Snapshot:
        if self._frozen is None:
            self._frozen = Layered(dict(self.entities))
        else:
            self._frozen = self._frozen.evolve({t: self.entities.get(t, GONE) for t in self._touched})
        self._touched = set()
        contents = {place: frozenset(self._contents.get(place, ())) or GONE for place in self._moved}
        if self._frozen_contents is None:
            self._frozen_contents = Layered({p: frozenset(ids) for p, ids in self._contents.items()})
        else:
            self._frozen_contents = self._frozen_contents.evolve(contents)
        self._moved = set()
        assert self.order is not None  # built with the index
        table = EntityTable(self._frozen, self.order)
        return Snapshot(revision=revision, entities=table, names=dict(self.names),
                        skipped=frozenset(self.skipped), changed=changed, contents=self._frozen_contents)

    # --- names and classes ---------------------------------------------------------------------

    def labels(self, term: str) -> tuple[str, ...]:
        if term not in self._labels:
            found = self.kb.find(f"{_pattern_term(term)} rdfs:label ?l")
            self._labels[term] = tuple(dict.fromkeys(str(r["l"]) for r in found if isinstance(r["l"], str)))
        return self._labels[term]

    def display(self, term: str) -> str:
        """The label in the wanted language first (D17); other languages still match in the lexicon."""
        if term not in self._display:
            self._display[term] = self.kb.label(term, self.lang) if self.labels(term) else readable_id(term)
        return self._display[term]

    def _words(self, klass: str, asserted: bool) -> tuple[str, ...]:
        # An unlabelled asserted class still names its instances ("Remote" -> "remote"); unlabelled
        # inferred superclasses (cyc:SpatialThing...) would only add noise.
        key = (klass, asserted)
        if key not in self._class_words:
            found = self.labels(klass)
            names = [self.display(klass), *found] if found or asserted else []
            self._class_words[key] = tuple(dict.fromkeys(n.lower() for n in names))
        return self._class_words[key]

    def _core(self, term: str) -> _Core | None:
        if term in self._cores:
            return self._cores[term]
        try:
            all_classes = self.kb.classesof(term)
            labels = self.labels(term)
        except KbError:
            self._cores[term] = None  # a literal used as a place ("x isIn 'garden'") is not an entity
            return None
        if set(all_classes) & SCHEMA_TYPES:
            schema = _Core((), (), (), "thing", readable_id(term), schema=True, typed=True)
            self._cores[term] = schema
            return schema
        direct = [c for c in self.kb.classesof(term, direct=True) if c not in IGNORED_CLASSES]
        inferred = sorted(c for c in all_classes if c not in IGNORED_CLASSES and c not in direct)
        class_names = tuple(dict.fromkeys(
            name for c in (*direct, *inferred) for name in self._words(c, asserted=c in direct)
        ))
        for klass in (*direct, *inferred):
            self._users.setdefault(klass, set()).add(term)
        own = tuple(dict.fromkeys([self.display(term), *labels])) if labels else ()
        classes = set(all_classes)
        kind: Kind = "robot" if term == ROBOT_ID else next((k for cs, k in _KINDS if classes & cs), "thing")
        name = own[0] if own else (class_names[0] if class_names else readable_id(term))
        core = _Core(own, (*direct, *inferred), class_names, kind, name, schema=False,
                     typed=bool(all_classes))
        self._cores[term] = core
        return core

    # --- bookkeeping ---------------------------------------------------------------------------

    def _reorder(self, term: str, rank: int | None) -> None:
        old = self._rank.get(term)
        if old == rank:
            return
        if old is not None:
            if self.order is not None:
                self.order = self.order.remove((old, term))
            del self._rank[term]
        if rank is not None:
            if self.order is not None:
                self.order = self.order.insert((rank, term))
            self._rank[term] = rank

    def _drop(self, term: str) -> None:
        if self.entities.pop(term, None) is not None:
            self._touched.add(term)
        self.skipped.discard(term)
        self._set_hue(term, None)
        self._reorder(term, None)
        self._locate(term, (None, None))

    def _locate(self, term: str, places: tuple[str | None, ...]) -> None:
        """Keep `_contents` to the entities each support, zone or container holds."""
        old = self._located.get(term, (None, None))
        if places == old:
            return
        for place in old:
            if place is not None and place not in places:
                held = self._contents[place]
                held.discard(term)
                if not held:
                    del self._contents[place]
                self._moved.add(place)
        for place in places:
            if place is not None and place not in old:
                self._contents.setdefault(place, set()).add(term)
                self._moved.add(place)
        if not any(places):
            self._located.pop(term, None)
        else:
            self._located[term] = places

    def _set_hue(self, term: str, hue: str | None) -> None:
        old = self._hue.get(term)
        if old == hue:
            return
        if old is not None:
            users = self._hue_users[old]
            users.discard(term)
            if not users:
                del self._hue_users[old]
            del self._hue[term]
        if hue is not None:
            self._hue[term] = hue
            self._hue_users.setdefault(hue, set()).add(term)

    def _place(self, term: str) -> None:
        """Keep `names` to the display names of the supports, zones and related things some
        subject shows."""
        places = tuple(self.facts.value(table, term) for table in PLACES)
        shown = (*places, *(other for _prep, other in self.facts.relations(term)))
        old = self._placed.get(term, ())
        if shown == old:
            return
        for value in old:
            if value is not None:
                self._refs[value] -= 1
                if not self._refs[value]:
                    del self._refs[value]
                    self.names.pop(value, None)
        for value in shown:
            if value is not None:
                self._refs[value] += 1
                if value not in self.names:
                    self.names[value] = self.display(value)
        if any(v is not None for v in shown):
            self._placed[term] = shown
        else:
            self._placed.pop(term, None)


def _pattern_term(term: str) -> str:
    """A term as the KB printed it, made usable in a pattern again (full IRIs need angle brackets)."""
    return f"<{term}>" if "://" in term else term
