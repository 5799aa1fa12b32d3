"""The entities of the situation, maintained from what each commit changed.

`EntityIndex` holds the mutable state behind the snapshots: the facts (`facts.Facts`), each
candidate's classes and names (read for the whole KB at once by the first build, then asked of the
KB again only when a term's types or labels change), display names per term, and the entities in
their deterministic order (shared sorted chunks). A commit touching N statements costs O(N) KB
questions and updates; `freeze` makes an immutable `Snapshot` of the state (the entities as a
`layered.Layered` version of the last snapshot's: no sorting, no copy of the world, no KB access).
Entities with the same classes share one tuple of classes and one of class names.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from dialogue.reference.facts import PERSON_CLASSES, ROBOT_ID, ZONE_CLASSES, Change, Facts, Triple
from dialogue.reference.layered import GONE, Gone, Layered, SortedChunks, layered, rebucket
from dialogue.reference.snapshot import (
    IGNORED_CLASSES,
    ROBOT_CLASSES,
    SCHEMA_TYPES,
    VALUE_CLASSES,
    VALUE_TERMS,
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


_Strings = tuple[str, ...]

#: The classes of what is never an entity: schema terms and the ontology's values.
_NOT_ENTITIES = SCHEMA_TYPES | VALUE_CLASSES


@dataclass(frozen=True, slots=True)
class _Core:
    """What the KB says of a term itself (asked again only when its types or labels change)."""

    labels: tuple[str, ...]
    classes: tuple[str, ...]
    class_names: tuple[str, ...]
    kind: Kind
    name: str
    #: A schema term (class, property...) or one of the ontology's values (a colour): never an entity.
    schema: bool
    #: Has any class: an unseen untyped term is no entity either.
    typed: bool


class EntityIndex:
    """Mutable; used by one thread at a time (the grounder serialises its builds)."""

    def __init__(self, kb: KnowledgeBase, lang: str = "en") -> None:
        self.kb = kb
        self.lang = lang
        # The labels are read once, for the facts (who is named) and for each term's own labels.
        labelled = kb.find("?x rdfs:label ?l")
        self.facts = Facts.load(kb, labelled)
        self._cores: dict[str, _Core | None] = {}  # None: not a term the KB can describe
        self._labels: dict[str, tuple[str, ...]] = {}
        self._display: dict[str, str] = {}
        self._class_words: dict[tuple[str, bool], tuple[str, ...]] = {}
        #: Terms by the classes of their core, and each class to the class tuples it is in: whose
        #: names change when a class's do (one entry per term, not one per term and class).
        self._members: dict[tuple[str, ...], set[str]] = {}
        self._users: dict[str, set[tuple[str, ...]]] = {}
        self._shared: dict[_Strings, _Strings] = {}  # one copy of each tuple of classes or names
        #: (classes, asserted classes) -> (the classes in entity order, their names); emptied when
        #: a class's names change.
        self._kinds: dict[tuple[_Strings, _Strings], tuple[_Strings, _Strings]] = {}
        #: The whole KB's classes (all, then asserted) and display names, read once by the first
        #: build and dropped after it.
        self._bulk: tuple[dict[str, list[str]], dict[str, list[str]], dict[str, str]] | None = None
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
        self._frozen_contents: Layered[str, Mapping[str, None]] | None = None
        #: What each place gained (None) or lost (GONE) since the last snapshot: a zone holds a
        #: tenth of the world, and copying its contents for every thing moved in or out made each
        #: tick cost the zone's size (issue 32: milliseconds at 300k).
        self._moved: dict[str, dict[str, Gone | None]] = {}
        self._frozen_names: Layered[str, str] | None = None
        self._renamed: dict[str, str | Gone] = {}  # `names` changed since the last snapshot
        self._rank: dict[str, int] = {}
        #: (rank, id) of every entity, sorted; shared by the snapshots it did not change in.
        self.order: SortedChunks[tuple[int, str]] | None = None  # None: built at the end of __init__
        self.skipped: set[str] = set()
        self._prefetch(labelled)
        for term in sorted(self.facts.candidates()):
            self.update(term)
        self._bulk = None
        self.order = SortedChunks((rank, term) for term, rank in self._rank.items())

    def _prefetch(self, labelled: list[dict[str, Any]]) -> None:
        """Every term's classes and labels at once: a few questions about the whole KB rather than
        a few per entity (the per-question cost dominated a first build: seconds at 100k)."""
        kb = self.kb
        self._bulk = (kb.all_classes(), kb.all_classes(direct=True), kb.all_labels(self.lang))
        labels: dict[str, list[str]] = {}
        for row in labelled:  # sorted: each term's labels in the order `labels` gives
            if isinstance(row["l"], str):
                labels.setdefault(row["x"], []).append(row["l"])
        self._labels = {term: tuple(dict.fromkeys(found)) for term, found in labels.items()}
        for term in self.facts.candidates():  # none found: none to ask for
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
                if self._class_words.pop((term, asserted), None) is not None:
                    self._kinds.clear()
            for classes in self._users.get(term, ()):
                deep |= self._members.get(classes, set())
            shallow |= self._hue_users.get(term, set())
            if term in self.names:
                self.names[term] = self._renamed[term] = self.display(term)
        for term in deep:
            self._drop_core(term)
        for term in deep | shallow:
            self.update(term)
        return deep | shallow

    def _forget(self, term: str) -> None:
        self._labels.pop(term, None)
        self._display.pop(term, None)

    def update(self, term: str) -> None:
        """Recompute one term's entity from the facts and its (cached) core."""
        facts = self.facts
        support, zone = facts.value("support", term), facts.value("zone", term)
        relations = facts.relations(term, zone)
        self._place(term, (support, zone, *(other for _prep, other in relations)))
        core = self._core(term) if facts.is_candidate(term) else None
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
            support=support, zone=zone, colour=self.display(hue) if hue else None,
            engagement=facts.value("engagement", term), owner=facts.value("owner", term), relations=relations,
            movable=_boolean(facts.value("movable", term)),
            kin=facts.kin(term) if core.kind == "person" else (),
        )  # fmt: skip
        self._reorder(term, rank(self.entities[term]))
        self._locate(term, (support, zone, *(other for prep, other in relations if prep == "in")))

    def freeze(self, revision: int, changed: tuple[tuple[int, frozenset[str]], ...] = ()) -> Snapshot:
        if self._frozen is None:
            self._frozen = Layered(dict(self.entities))
        else:
            self._frozen = self._frozen.evolve({t: self.entities.get(t, GONE) for t in self._touched})
        self._touched = set()
        held, moved = self._frozen_contents, self._moved
        if held is None:
            self._frozen_contents = Layered({p: layered(dict.fromkeys(i)) for p, i in self._contents.items()})
        else:
            self._frozen_contents = held.evolve({p: rebucket(held.get(p), ids) for p, ids in moved.items()})
        self._moved = {}
        if self._frozen_names is None:
            self._frozen_names = Layered(dict(self.names))
        else:
            self._frozen_names = self._frozen_names.evolve(self._renamed)
        self._renamed = {}
        assert self.order is not None  # built with the index
        table = EntityTable(self._frozen, self.order)
        return Snapshot(revision=revision, entities=table, names=self._frozen_names,
                        skipped=frozenset(self.skipped), changed=changed, contents=self._frozen_contents)

    # --- names and classes ---------------------------------------------------------------------

    def _drop_core(self, term: str) -> None:
        core = self._cores.pop(term, None)
        if core is not None and core.classes:
            members = self._members[core.classes]
            members.discard(term)
            if not members:
                del self._members[core.classes]
                for klass in core.classes:
                    users = self._users[klass]
                    users.discard(core.classes)
                    if not users:
                        del self._users[klass]

    def _classes(self, every: _Strings, asserted: _Strings) -> tuple[_Strings, _Strings]:
        """A term's classes (its own first) and their names, by its classes and asserted classes:
        made once for all the terms of the same classes."""
        key = (every, asserted)
        found = self._kinds.get(key)
        if found is None:
            direct = [c for c in asserted if c not in IGNORED_CLASSES]
            inferred = sorted(c for c in every if c not in IGNORED_CLASSES and c not in direct)
            classes = self._share((*direct, *inferred))
            names = dict.fromkeys(name for c in classes for name in self._words(c, asserted=c in direct))
            found = self._kinds[key] = (classes, self._share(tuple(names)))
        return found

    def _share(self, values: tuple[str, ...]) -> tuple[str, ...]:
        return self._shared.setdefault(values, values)

    def labels(self, term: str) -> tuple[str, ...]:
        if term not in self._labels:
            found = self.kb.find(f"{_pattern_term(term)} rdfs:label ?l")
            self._labels[term] = tuple(dict.fromkeys(str(r["l"]) for r in found if isinstance(r["l"], str)))
        return self._labels[term]

    def display(self, term: str) -> str:
        """The label in the wanted language first (D17); other languages still match in the lexicon."""
        if term not in self._display:
            shown = self._bulk[2].get(term) if self._bulk is not None else None
            if shown is None:
                shown = self.kb.label(term, self.lang) if self.labels(term) else readable_id(term)
            elif not self.labels(term):  # only labels that are no text: named by its id, as `label` would
                shown = readable_id(term)
            if shown == term and self.labels(term):
                # A label in the language that only spells the id out (the ontology's "myself"@en)
                # names nothing: a scene's own label of no language ("Pip") is the name.
                shown = self.kb.label(term)
            self._display[term] = shown
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
        bulk = self._bulk
        try:
            all_classes = bulk[0][term] if bulk is not None and term in bulk[0] else self.kb.classesof(term)
            labels = self.labels(term)
        except KbError:
            self._cores[term] = None  # a literal used as a place ("x isIn 'garden'") is not an entity
            return None
        if not _NOT_ENTITIES.isdisjoint(all_classes) or term in VALUE_TERMS:
            schema = _Core((), (), (), "thing", readable_id(term), schema=True, typed=True)
            self._cores[term] = schema
            return schema
        asserted = bulk[1].get(term, []) if bulk is not None and term in bulk[0] else \
            self.kb.classesof(term, direct=True)
        classes, class_names = self._classes(tuple(all_classes), tuple(asserted))
        if classes:
            members = self._members.get(classes)
            if members is None:  # the first term of these classes: each class is used by them
                members = self._members[classes] = set()
                for klass in classes:
                    self._users.setdefault(klass, set()).add(classes)
            members.add(term)
        own = tuple(dict.fromkeys([self.display(term), *labels])) if labels else ()
        kinds = (k for cs, k in _KINDS if cs.intersection(all_classes))
        kind: Kind = "robot" if term == ROBOT_ID else next(kinds, "thing")
        name = own[0] if own else (class_names[0] if class_names else readable_id(term))
        core = _Core(own, classes, class_names, kind, name, schema=False, typed=bool(all_classes))
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
                if self._frozen_contents is not None:  # (a first build's are all new)
                    self._moved.setdefault(place, {})[term] = GONE
        for place in places:
            if place is not None and place not in old:
                self._contents.setdefault(place, set()).add(term)
                if self._frozen_contents is not None:
                    self._moved.setdefault(place, {})[term] = None
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

    def _place(self, term: str, shown: tuple[str | None, ...]) -> None:
        """Keep `names` to the display names of the supports, zones and related things some
        subject shows (``shown``: its support, its zone, then the other things it relates to)."""
        old = self._placed.get(term, ())
        if shown == old:
            return
        for value in old:
            if value is not None:
                self._refs[value] -= 1
                if not self._refs[value]:
                    del self._refs[value]
                    if self.names.pop(value, None) is not None:
                        self._renamed[value] = GONE
        for value in shown:
            if value is not None:
                self._refs[value] += 1
                if value not in self.names:
                    self.names[value] = self._renamed[value] = self.display(value)
        if any(v is not None for v in shown):
            self._placed[term] = shown
        else:
            self._placed.pop(term, None)


def _pattern_term(term: str) -> str:
    """A term as the KB printed it, made usable in a pattern again (full IRIs need angle brackets)."""
    return f"<{term}>" if "://" in term else term


def _boolean(value: str | None) -> bool | None:
    """A boolean fact's value as the KB gives it ("true", "False", "1"...), None when absent."""
    if value is None:
        return None
    return value.strip().lower() in {"true", "1"}
