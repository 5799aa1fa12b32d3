"""An in-memory triple index with the three access paths the join and the reasoner need.

rdflib's Memory store answers single patterns well but its SPARQL join ignores statistics
(kb-compat §8.5); the KB keeps its own dictionaries so that every pattern with at least one
bound position is a couple of hash lookups, and counts are exact and cheap for the planner.

Compact: most (subject, predicate) pairs have one object and most (object, subject) pairs one
predicate, so a leaf of the index holds a lone term itself and becomes a set only from its second
term on (an empty Python set costs 216 bytes: a set per leaf was two thirds of the KB's memory).
Every term is interned, so a lone leaf is compared by identity first.
"""

from __future__ import annotations

from collections.abc import Collection, Iterator, Mapping
from typing import Any

from kb.terms import Node, Triple

_EMPTY: frozenset[Node] = frozenset()
Leaf = Node | set[Node]
Level = dict[Node, dict[Node, Leaf]]


class Interner:
    """One canonical object per term, shared by the indexes of a KB.

    rdflib terms compare with a Python-level ``__eq__``; when every index holds the very same
    object for a term, dictionary lookups stop at the identity check and joins get several
    times faster. Terms no index uses any more are pruned from time to time.
    """

    __slots__ = ("_next_prune", "_terms", "shorts")

    def __init__(self) -> None:
        self._terms: dict[Node, Node] = {}
        self._next_prune = 50_000
        #: The output form of the terms answers have named (``kb.terms.shorten``), made once.
        self.shorts: dict[Node, Any] = {}

    def __len__(self) -> int:
        return len(self._terms)

    def intern(self, term: Node) -> Node:
        return self._terms.setdefault(term, term)

    def canonical(self, term: Node) -> Node:
        return self._terms.get(term, term)

    def triple(self, triple: Triple) -> Triple:
        """The triple made of the canonical terms (interning new ones)."""
        intern = self._terms.setdefault
        s, p, o = triple
        return (intern(s, s), intern(p, p), intern(o, o))

    def prune_if_large(self, indexes: list[TripleIndex]) -> None:
        if len(self._terms) < self._next_prune:
            return
        self._terms = {t: t for t in self._terms if any(ix.uses(t) for ix in indexes)}
        self.shorts = {t: v for t, v in self.shorts.items() if t in self._terms}
        self._next_prune = max(50_000, 2 * len(self._terms))


def members(leaf: Leaf) -> Collection[Node]:
    """The terms of a leaf: the set itself, or the lone term as a 1-tuple."""
    return leaf if isinstance(leaf, set) else (leaf,)


def _holds(leaf: Leaf, term: Node) -> bool:
    if isinstance(leaf, set):
        return term in leaf
    # Interned terms are identical; str's own == (C) rules out the rest before rdflib's __eq__.
    return leaf is term or (_same_text(leaf, term) and leaf == term)


_same_text = str.__eq__


def _put(inner: dict[Node, Leaf], key: Node, term: Node) -> bool:
    leaf = inner.get(key)
    if leaf is None:
        inner[key] = term
        return True
    if isinstance(leaf, set):
        if term in leaf:
            return False
        leaf.add(term)
        return True
    if leaf is term or (_same_text(leaf, term) and leaf == term):
        return False
    inner[key] = {leaf, term}
    return True


def _take(index: Level, a: Node, b: Node, c: Node) -> None:
    """Remove c from the leaf (a, b), which holds it; empty containers are dropped."""
    inner = index[a]
    leaf = inner[b]
    if isinstance(leaf, set):
        leaf.discard(c)
        if len(leaf) == 1:
            inner[b] = next(iter(leaf))
        return
    del inner[b]
    if not inner:
        del index[a]


class LeafView(Mapping[Node, Collection[Node]]):
    """A read-only view of one level of the index: key -> its terms, as a set."""

    __slots__ = ("_inner",)

    def __init__(self, inner: Mapping[Node, Leaf]) -> None:
        self._inner = inner

    def __getitem__(self, key: Node) -> Collection[Node]:
        return _as_set(self._inner[key])

    def __iter__(self) -> Iterator[Node]:
        return iter(self._inner)

    def __len__(self) -> int:
        return len(self._inner)

    def items(self) -> Iterator[tuple[Node, Collection[Node]]]:  # type: ignore[override]
        return ((key, _as_set(leaf)) for key, leaf in self._inner.items())


class TripleIndex:
    """A set of triples indexed as subject→predicate→objects, predicate→object→subjects and
    (unless ``by_object`` is False) object→subject→predicates. Without the third path, patterns
    with only the object bound are answered through the second (a model's asserted triples are
    only ever read by subject or by predicate: they need not pay for it)."""

    __slots__ = ("_interner", "_osp", "_pcount", "_pos", "_size", "_spo")

    def __init__(self, interner: Interner | None = None, by_object: bool = True) -> None:
        self._interner = interner if interner is not None else Interner()
        self._spo: Level = {}
        self._pos: Level = {}
        self._osp: Level | None = {} if by_object else None
        self._pcount: dict[Node, int] = {}
        self._size = 0

    def __len__(self) -> int:
        return self._size

    def __contains__(self, triple: Triple) -> bool:
        s, p, o = triple
        by_p = self._spo.get(s)
        if by_p is None:
            return False
        leaf = by_p.get(p)
        return leaf is not None and _holds(leaf, o)

    def __iter__(self) -> Iterator[Triple]:
        for s, by_p in self._spo.items():
            for p, leaf in by_p.items():
                if isinstance(leaf, set):
                    for o in leaf:
                        yield (s, p, o)
                else:
                    yield (s, p, leaf)

    @property
    def interner(self) -> Interner:
        return self._interner

    def canonical(self, term: Node) -> Node:
        return self._interner.canonical(term)

    def uses(self, term: Node) -> bool:
        return term in self._spo or term in self._pos or self.is_object(term)

    def add(self, s: Node, p: Node, o: Node) -> bool:
        """Add a triple; True if it was not there."""
        intern = self._interner.intern
        return self.insert(intern(s), intern(p), intern(o))

    def insert(self, s: Node, p: Node, o: Node) -> bool:
        """``add`` for terms that are already this index's interned ones (the model's and the
        reasoner's, which build triples from them): no interning. Other terms are still stored
        correctly, only compared more slowly."""
        by_p = self._spo.get(s)
        if by_p is None:
            by_p = self._spo[s] = {}
        if not _put(by_p, p, o):
            return False
        by_o = self._pos.get(p)
        if by_o is None:
            by_o = self._pos[p] = {}
        _put(by_o, o, s)
        if self._osp is not None:
            by_s = self._osp.get(o)
            if by_s is None:
                by_s = self._osp[o] = {}
            _put(by_s, s, p)
        self._pcount[p] = self._pcount.get(p, 0) + 1
        self._size += 1
        return True

    def remove(self, s: Node, p: Node, o: Node) -> bool:
        """Remove a triple; True if it was there. Empty inner containers are dropped."""
        canonical = self._interner.canonical
        s, p, o = canonical(s), canonical(p), canonical(o)
        if (s, p, o) not in self:
            return False
        _take(self._spo, s, p, o)
        _take(self._pos, p, o, s)
        if self._osp is not None:
            _take(self._osp, o, s, p)
        left = self._pcount[p] - 1
        if left:
            self._pcount[p] = left
        else:
            del self._pcount[p]
        self._size -= 1
        return True

    def clear(self) -> None:
        self._spo.clear()
        self._pos.clear()
        if self._osp is not None:
            self._osp.clear()
        self._pcount.clear()
        self._size = 0

    # --- point access -------------------------------------------------------------------

    def objects(self, s: Node, p: Node) -> set[Node] | frozenset[Node]:
        by_p = self._spo.get(s)
        leaf = None if by_p is None else by_p.get(p)
        return _as_set(leaf)

    def subjects(self, p: Node, o: Node) -> set[Node] | frozenset[Node]:
        by_o = self._pos.get(p)
        leaf = None if by_o is None else by_o.get(o)
        return _as_set(leaf)

    def predicates(self, s: Node, o: Node) -> set[Node] | frozenset[Node]:
        if self._osp is None:
            by_p = self._spo.get(s, {})
            return frozenset(p for p, leaf in by_p.items() if _holds(leaf, o))
        by_s = self._osp.get(o)
        leaf = None if by_s is None else by_s.get(s)
        return _as_set(leaf)

    def has_subject_predicate(self, s: Node, p: Node) -> bool:
        by_p = self._spo.get(s)
        return by_p is not None and p in by_p

    def has_predicate_object(self, p: Node, o: Node) -> bool:
        by_o = self._pos.get(p)
        return by_o is not None and o in by_o

    def out_edges(self, s: Node) -> Mapping[Node, Collection[Node]]:
        """predicate → objects of one subject."""
        return LeafView(self._spo.get(s, {}))

    def in_edges(self, o: Node) -> Mapping[Node, Collection[Node]]:
        """subject → predicates of one object."""
        if self._osp is not None:
            return LeafView(self._osp.get(o, {}))
        found: dict[Node, set[Node]] = {}
        for p, by_o in self._pos.items():
            leaf = by_o.get(o)
            if leaf is not None:
                for s in members(leaf):
                    found.setdefault(s, set()).add(p)
        return found

    def by_predicate(self, p: Node) -> Mapping[Node, Collection[Node]]:
        """object → subjects for one predicate."""
        return LeafView(self._pos.get(p, {}))

    def subject_terms(self) -> Iterator[Node]:
        return iter(self._spo)

    def predicate_terms(self) -> Iterator[Node]:
        return iter(self._pos)

    def object_terms(self) -> Iterator[Node]:
        if self._osp is not None:
            return iter(self._osp)
        return iter({o: None for by_o in self._pos.values() for o in by_o})

    def is_subject(self, term: Node) -> bool:
        return term in self._spo

    def is_predicate(self, term: Node) -> bool:
        return term in self._pos

    def is_object(self, term: Node) -> bool:
        if self._osp is not None:
            return term in self._osp
        return any(term in by_o for by_o in self._pos.values())

    # --- patterns -----------------------------------------------------------------------

    def triples(self, s: Node | None, p: Node | None, o: Node | None) -> Iterator[Triple]:
        """Every triple matching the pattern (``None`` is a wildcard), from a copy: the caller
        may change the index while iterating."""
        yield from list(self.scan(s, p, o))

    def scan(self, s: Node | None, p: Node | None, o: Node | None) -> Iterator[Triple]:  # noqa: C901
        """Like ``triples`` but without copying: the index must not change while iterating
        (the KB lock guarantees it for queries)."""
        if s is not None:
            by_p = self._spo.get(s)
            if by_p is None:
                return
            if p is not None:
                leaf = by_p.get(p)
                if leaf is None:
                    return
                if o is None:
                    for obj in members(leaf):
                        yield (s, p, obj)
                elif _holds(leaf, o):
                    yield (s, p, o)
                return
            if o is not None:
                for pred in self.predicates(s, o):
                    yield (s, pred, o)
                return
            for pred, leaf in by_p.items():
                for obj in members(leaf):
                    yield (s, pred, obj)
            return
        if p is not None:
            by_o = self._pos.get(p)
            if by_o is None:
                return
            if o is not None:
                leaf = by_o.get(o)
                if leaf is not None:
                    for subj in members(leaf):
                        yield (subj, p, o)
                return
            for obj, leaf in by_o.items():
                for subj in members(leaf):
                    yield (subj, p, obj)
            return
        if o is not None:
            for subj, preds in self.in_edges(o).items():
                for pred in preds:
                    yield (subj, pred, o)
            return
        yield from self

    def count(self, s: Node | None, p: Node | None, o: Node | None) -> int:
        """The exact number of matches of a pattern."""
        if s is not None:
            by_p = self._spo.get(s)
            if by_p is None:
                return 0
            if p is not None:
                leaf = by_p.get(p)
                if leaf is None:
                    return 0
                if o is not None:
                    return 1 if _holds(leaf, o) else 0
                return len(leaf) if isinstance(leaf, set) else 1
            if o is not None:
                return len(self.predicates(s, o))
            return sum(len(leaf) if isinstance(leaf, set) else 1 for leaf in by_p.values())
        if p is not None:
            if o is not None:
                by_o = self._pos.get(p)
                leaf = None if by_o is None else by_o.get(o)
                return 0 if leaf is None else len(leaf) if isinstance(leaf, set) else 1
            return self._pcount.get(p, 0)
        if o is not None:
            return sum(len(preds) for preds in self.in_edges(o).values())
        return self._size


def _as_set(leaf: Leaf | None) -> set[Node] | frozenset[Node]:
    if leaf is None:
        return _EMPTY
    if isinstance(leaf, set):
        return leaf
    return frozenset((leaf,))
