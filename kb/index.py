"""An in-memory triple index with the three access paths the join and the reasoner need.

rdflib's Memory store answers single patterns well but its SPARQL join ignores statistics
(kb-compat §8.5); the KB keeps its own dictionaries so that every pattern with at least one
bound position is a couple of hash lookups, and counts are exact and cheap for the planner.
"""

from __future__ import annotations

from collections.abc import Iterator

from kb.terms import Node, Triple

_EMPTY: frozenset[Node] = frozenset()


class Interner:
    """One canonical object per term, shared by the indexes of a KB.

    rdflib terms compare with a Python-level ``__eq__``; when every index holds the very same
    object for a term, dictionary lookups stop at the identity check and joins get several
    times faster. Terms no index uses any more are pruned from time to time.
    """

    __slots__ = ("_next_prune", "_terms")

    def __init__(self) -> None:
        self._terms: dict[Node, Node] = {}
        self._next_prune = 50_000

    def __len__(self) -> int:
        return len(self._terms)

    def intern(self, term: Node) -> Node:
        return self._terms.setdefault(term, term)

    def canonical(self, term: Node) -> Node:
        return self._terms.get(term, term)

    def prune_if_large(self, indexes: list[TripleIndex]) -> None:
        if len(self._terms) < self._next_prune:
            return
        self._terms = {t: t for t in self._terms if any(ix.uses(t) for ix in indexes)}
        self._next_prune = max(50_000, 2 * len(self._terms))


class TripleIndex:
    """A set of triples indexed as subject→predicate→objects, predicate→object→subjects and
    object→subject→predicates."""

    __slots__ = ("_interner", "_osp", "_pcount", "_pos", "_size", "_spo")

    def __init__(self, interner: Interner | None = None) -> None:
        self._interner = interner if interner is not None else Interner()
        self._spo: dict[Node, dict[Node, set[Node]]] = {}
        self._pos: dict[Node, dict[Node, set[Node]]] = {}
        self._osp: dict[Node, dict[Node, set[Node]]] = {}
        self._pcount: dict[Node, int] = {}
        self._size = 0

    def __len__(self) -> int:
        return self._size

    def __contains__(self, triple: Triple) -> bool:
        s, p, o = triple
        by_p = self._spo.get(s)
        if by_p is None:
            return False
        objs = by_p.get(p)
        return objs is not None and o in objs

    def __iter__(self) -> Iterator[Triple]:
        for s, by_p in self._spo.items():
            for p, objs in by_p.items():
                for o in objs:
                    yield (s, p, o)

    @property
    def interner(self) -> Interner:
        return self._interner

    def canonical(self, term: Node) -> Node:
        return self._interner.canonical(term)

    def uses(self, term: Node) -> bool:
        return term in self._spo or term in self._pos or term in self._osp

    def add(self, s: Node, p: Node, o: Node) -> bool:
        """Add a triple; True if it was not there."""
        intern = self._interner.intern
        s, p, o = intern(s), intern(p), intern(o)
        objs = self._spo.setdefault(s, {}).setdefault(p, set())
        if o in objs:
            return False
        objs.add(o)
        self._pos.setdefault(p, {}).setdefault(o, set()).add(s)
        self._osp.setdefault(o, {}).setdefault(s, set()).add(p)
        self._pcount[p] = self._pcount.get(p, 0) + 1
        self._size += 1
        return True

    def remove(self, s: Node, p: Node, o: Node) -> bool:
        """Remove a triple; True if it was there. Empty inner containers are dropped."""
        by_p = self._spo.get(s)
        if by_p is None:
            return False
        objs = by_p.get(p)
        if objs is None or o not in objs:
            return False
        _discard(self._spo, s, p, o)
        _discard(self._pos, p, o, s)
        _discard(self._osp, o, s, p)
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
        self._osp.clear()
        self._pcount.clear()
        self._size = 0

    # --- point access -------------------------------------------------------------------

    def objects(self, s: Node, p: Node) -> set[Node] | frozenset[Node]:
        by_p = self._spo.get(s)
        if by_p is None:
            return _EMPTY
        return by_p.get(p, _EMPTY)

    def subjects(self, p: Node, o: Node) -> set[Node] | frozenset[Node]:
        by_o = self._pos.get(p)
        if by_o is None:
            return _EMPTY
        return by_o.get(o, _EMPTY)

    def predicates(self, s: Node, o: Node) -> set[Node] | frozenset[Node]:
        by_s = self._osp.get(o)
        if by_s is None:
            return _EMPTY
        return by_s.get(s, _EMPTY)

    def has_subject_predicate(self, s: Node, p: Node) -> bool:
        by_p = self._spo.get(s)
        return by_p is not None and p in by_p

    def has_predicate_object(self, p: Node, o: Node) -> bool:
        by_o = self._pos.get(p)
        return by_o is not None and o in by_o

    def out_edges(self, s: Node) -> dict[Node, set[Node]]:
        return self._spo.get(s, {})

    def in_edges(self, o: Node) -> dict[Node, set[Node]]:
        return self._osp.get(o, {})

    def by_predicate(self, p: Node) -> dict[Node, set[Node]]:
        """object → subjects for one predicate."""
        return self._pos.get(p, {})

    def subject_terms(self) -> Iterator[Node]:
        return iter(self._spo)

    def predicate_terms(self) -> Iterator[Node]:
        return iter(self._pos)

    def object_terms(self) -> Iterator[Node]:
        return iter(self._osp)

    def is_subject(self, term: Node) -> bool:
        return term in self._spo

    def is_predicate(self, term: Node) -> bool:
        return term in self._pos

    def is_object(self, term: Node) -> bool:
        return term in self._osp

    # --- patterns -----------------------------------------------------------------------

    def triples(self, s: Node | None, p: Node | None, o: Node | None) -> Iterator[Triple]:
        """Every triple matching the pattern (``None`` is a wildcard), from a copy: the caller
        may change the index while iterating."""
        yield from list(self.scan(s, p, o))

    def scan(self, s: Node | None, p: Node | None, o: Node | None) -> Iterator[Triple]:
        """Like ``triples`` but without copying: the index must not change while iterating
        (the KB lock guarantees it for queries)."""
        if s is not None:
            by_p = self._spo.get(s)
            if by_p is None:
                return
            if p is not None:
                objs = by_p.get(p)
                if objs is not None:
                    if o is None:
                        for obj in objs:
                            yield (s, p, obj)
                    elif o in objs:
                        yield (s, p, o)
                return
            if o is not None:
                for pred in self.predicates(s, o):
                    yield (s, pred, o)
                return
            for pred, objs in by_p.items():
                for obj in objs:
                    yield (s, pred, obj)
            return
        if p is not None:
            by_o = self._pos.get(p)
            if by_o is None:
                return
            if o is not None:
                for subj in by_o.get(o, ()):
                    yield (subj, p, o)
                return
            for obj, subjs in by_o.items():
                for subj in subjs:
                    yield (subj, p, obj)
            return
        if o is not None:
            for subj, preds in self._osp.get(o, {}).items():
                for pred in preds:
                    yield (subj, pred, o)
            return
        yield from self

    def count(self, s: Node | None, p: Node | None, o: Node | None) -> int:
        """The exact number of matches of a pattern (an upper bound when only s or o is bound
        together with nothing else would be costlier to get exactly)."""
        if s is not None:
            by_p = self._spo.get(s)
            if by_p is None:
                return 0
            if p is not None:
                objs = by_p.get(p)
                if objs is None:
                    return 0
                return (1 if o in objs else 0) if o is not None else len(objs)
            if o is not None:
                return len(self.predicates(s, o))
            return sum(len(v) for v in by_p.values())
        if p is not None:
            if o is not None:
                return len(self.subjects(p, o))
            return self._pcount.get(p, 0)
        if o is not None:
            return sum(len(v) for v in self._osp.get(o, {}).values())
        return self._size


def _discard(index: dict[Node, dict[Node, set[Node]]], a: Node, b: Node, c: Node) -> None:
    inner = index[a]
    leaf = inner[b]
    leaf.discard(c)
    if not leaf:
        del inner[b]
        if not inner:
            del index[a]
