"""Incremental OWL RL materialisation: semi-naive insertion and delete-and-rederive (DRed).

The rules are the subset of OWL 2 RL that the ontology uses (kb-compat §7.3), driven by the
compiled TBox: cax-sco/cax-eqc (through the closed class hierarchy), prp-spo1/prp-eqp, prp-dom,
prp-rng, prp-inv, prp-symp, prp-trp, cls-hv1, cls-hv2, cls-int1 (cls-int2 and cls-uni are in the
hierarchy). Every rule has at most one premise besides the triple being processed, so a new
fact is joined only against the current closure.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from rdflib import Literal
from rdflib.namespace import RDF

from kb.errors import ReasoningTooLarge
from kb.index import TripleIndex
from kb.reasonbudget import StepBudget
from kb.tbox import CompiledTBox
from kb.terms import Node, Triple

TYPE = RDF.type
_same_text = str.__eq__  # C code: rules out most terms before rdflib's Python __eq__
# Steps counted before they are spent from a write's budget (a check per step would cost more).
_SPEND_EVERY = 1024
# What a triple new to the closure (or withdrawn from it) costs besides the step that found it: its
# place in the indexes (and taking it out again if the write is refused).
_NEW = 1


class Reasoner:
    """Keeps ``closure`` equal to the OWL RL closure of ``asserted`` under ``tbox``."""

    __slots__ = ("asserted", "closure", "tbox", "type")

    def __init__(self, tbox: CompiledTBox, asserted: TripleIndex, closure: TripleIndex) -> None:
        self.tbox = tbox
        self.asserted = asserted
        self.closure = closure
        self.type = closure.interner.intern(TYPE)  # the KB's own rdf:type, for the triples it derives

    def materialise(self) -> None:
        """Recompute the closure from the asserted triples (start-up, TBox change)."""
        self.closure.clear()
        self.insert(list(self.asserted))
        intern = self.closure.interner.triple
        self.insert([intern(t) for t in self.tbox.schema_closure()])

    def insert(self, triples: Iterable[Triple], budget: StepBudget | None = None) -> list[Triple]:
        """Add triples (already asserted, made of the KB's interned terms) to the closure; return
        every triple new to it. Derived triples are built from those terms and the TBox's, so
        they are interned too. Past the ``budget``'s steps, ``ReasoningTooLarge`` with the
        closure as it was.

        A new type gives all its superclasses at once (the table is closed), and the types that
        gives need not give theirs again (they are among them): only their other rules run."""
        insert = self.closure.insert
        added = [t for t in triples if insert(*t)]
        queue = list(added)
        tp, superclasses = self.type, self.tbox.superclasses
        steps = 0

        def derive(found: Iterable[Triple]) -> None:
            nonlocal steps
            for derived in found:
                steps += 1
                if insert(*derived):
                    steps += _NEW
                    added.append(derived)
                    queue.append(derived)

        try:
            while queue:
                triple = queue.pop()
                s, p, o = triple
                if p is tp or (_same_text(p, TYPE) and p == TYPE):
                    for sup in superclasses.get(o, ()):
                        if insert(s, tp, sup):
                            steps += _NEW
                            added.append((s, tp, sup))
                            derive(self._type_rules(s, sup))
                    derive(self._type_rules(s, o))
                else:
                    derive(self.consequences(triple))
                if budget is not None and steps >= _SPEND_EVERY:
                    budget.spend(steps)
                    steps = 0
            if budget is not None:
                budget.spend(steps)
        except ReasoningTooLarge:
            remove = self.closure.remove
            for t in added:
                remove(*t)
            raise
        return added

    def delete(self, triples: Iterable[Triple],
               budget: StepBudget | None = None) -> tuple[list[Triple], list[Triple]]:
        """Withdraw triples no longer asserted; return (removed, re-added) net of each other.
        Past the ``budget``'s steps, ``ReasoningTooLarge`` with the closure as it was.

        Over-deletion removes everything that has a derivation through a withdrawn fact; then
        each over-deleted fact with another one-step derivation from what is left comes back,
        and semi-naive insertion restores what follows from it.
        """
        closure, asserted = self.closure, self.asserted
        over: set[Triple] = set()
        queue = [t for t in triples if t in closure and t not in asserted]
        steps = 0
        while queue:
            t = queue.pop()
            if t in over:
                continue
            over.add(t)
            for derived in self.consequences(t):
                steps += 1
                if derived not in over and derived not in asserted and derived in closure:
                    queue.append(derived)
            if budget is not None and steps >= _SPEND_EVERY:
                budget.spend(steps)  # nothing has changed yet
                steps = 0
        if budget is not None:
            budget.spend(steps + len(over) * _NEW)
        for t in over:
            closure.remove(*t)
        try:
            back = self.insert([t for t in over if self.derivable(t)], budget)
        except ReasoningTooLarge:
            for t in over:
                closure.insert(*t)
            raise
        if not back:
            return list(over), []
        restored = set(back)
        return [t for t in over if t not in restored], [t for t in back if t not in over]

    def consequences(self, triple: Triple) -> Iterator[Triple]:
        """Every triple one rule step derives from ``triple`` and the closure."""
        s, p, o = triple
        tb, tp = self.tbox, self.type
        if p is tp or (_same_text(p, TYPE) and p == TYPE):
            for sup in tb.superclasses.get(o, ()):
                yield (s, tp, sup)
            yield from self._type_rules(s, o)
            return
        for sup in tb.superproperties.get(p, ()):
            yield (s, sup, o)
        for cls in tb.domains.get(p, ()):
            yield (s, tp, cls)
        for restriction in tb.restrictions_for.get((p, o), ()):
            yield (s, tp, restriction)
        if isinstance(o, Literal):
            return
        for cls in tb.ranges.get(p, ()):
            yield (o, tp, cls)
        for inv in tb.inverses.get(p, ()):
            yield (o, inv, s)
        if p in tb.symmetric:
            yield (o, p, s)
        if p in tb.transitive:
            closure = self.closure
            for z in list(closure.objects(o, p)):
                yield (s, p, z)
            for w in list(closure.subjects(p, s)):
                yield (w, p, o)

    def _type_rules(self, s: Node, o: Node) -> Iterator[Triple]:
        """What a type gives besides its superclasses: hasValue (cls-hv1), intersections (cls-int1)."""
        tb, tp = self.tbox, self.type
        pv = tb.has_value.get(o)
        if pv is not None:
            yield (s, pv[0], pv[1])
        for cls in tb.intersections_with.get(o, ()):
            if all((s, tp, m) in self.closure for m in tb.members[cls]):
                yield (s, tp, cls)

    def derivable(self, triple: Triple) -> bool:  # noqa: C901
        """True if one rule step derives ``triple`` from the closure without using itself."""
        if triple in self.asserted:
            return True
        s, p, o = triple
        tb, closure = self.tbox, self.closure
        tp = self.type
        if p is tp or (_same_text(p, TYPE) and p == TYPE):
            types = closure.objects(s, tp)
            subs = tb.subclasses.get(o)
            if subs and types:
                small, large = (subs, types) if len(subs) < len(types) else (types, subs)
                if any(c in large for c in small):
                    return True
            if any(closure.has_subject_predicate(s, q) for q in tb.domain_of.get(o, ())):
                return True
            if any(closure.has_predicate_object(q, s) for q in tb.range_of.get(o, ())):
                return True
            pv = tb.has_value.get(o)
            if pv is not None and (s, pv[0], pv[1]) in closure:
                return True
            items = tb.members.get(o)
            return items is not None and all(m in types for m in items)
        if any((s, q, o) in closure for q in tb.subproperties.get(p, ())):
            return True
        if any(((s, tp, r) in closure) for r in tb.restrictions_for.get((p, o), ())):
            return True
        if isinstance(o, Literal):
            return False
        if any((o, q, s) in closure for q in tb.inverses.get(p, ()) if (o, q, s) != triple):
            return True
        if p in tb.symmetric and s != o and (o, p, s) in closure:
            return True
        if p in tb.transitive:
            for z in closure.objects(s, p):
                if z != o and z != s and (z, p, o) in closure:
                    return True
        return False
