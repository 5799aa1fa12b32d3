"""The TBox compiled into lookup tables for the incremental reasoner (kb-compat §7.3).

Hierarchies are closed once here (subclass and subproperty closure through equivalences,
intersections and unions), so that one rule application gives every superclass of a new type
instead of climbing the hierarchy one step per reasoning round.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

from rdflib import BNode, Literal, URIRef
from rdflib.namespace import OWL, RDF, RDFS

from kb.tboxbudget import LinkCount, TBoxBounds
from kb.terms import Node, Triple

# Predicates whose triples change the compiled rules: adding or removing one recompiles.
SCHEMA_PREDICATES = frozenset(
    {
        RDFS.subClassOf, RDFS.subPropertyOf, RDFS.domain, RDFS.range, OWL.equivalentClass,
        OWL.equivalentProperty, OWL.inverseOf, OWL.intersectionOf, OWL.unionOf, OWL.onProperty,
        OWL.hasValue, RDF.first, RDF.rest,
    }
)
SCHEMA_TYPES = frozenset({OWL.TransitiveProperty, OWL.SymmetricProperty})
# Classes every individual belongs to: materialising them is noise (kb-compat §7.4, K11).
TOP_CLASSES = frozenset({OWL.Thing, RDFS.Resource})


def is_schema_triple(triple: Triple) -> bool:
    _, p, o = triple
    # C-level tests first: rdflib's == (and a literal's hash) are Python code, and every
    # written triple is tested.
    return p in SCHEMA_PREDICATES or (type(o) is URIRef and o in SCHEMA_TYPES and p == RDF.type)


@dataclass(frozen=True)
class CompiledTBox:
    """Rule tables; every mapping's values exclude the key itself."""

    superclasses: Mapping[Node, frozenset[Node]] = field(default_factory=dict)
    subclasses: Mapping[Node, frozenset[Node]] = field(default_factory=dict)
    superproperties: Mapping[Node, frozenset[Node]] = field(default_factory=dict)
    subproperties: Mapping[Node, frozenset[Node]] = field(default_factory=dict)
    domains: Mapping[Node, frozenset[Node]] = field(default_factory=dict)
    ranges: Mapping[Node, frozenset[Node]] = field(default_factory=dict)
    domain_of: Mapping[Node, frozenset[Node]] = field(default_factory=dict)
    range_of: Mapping[Node, frozenset[Node]] = field(default_factory=dict)
    inverses: Mapping[Node, frozenset[Node]] = field(default_factory=dict)
    symmetric: frozenset[Node] = frozenset()
    transitive: frozenset[Node] = frozenset()
    # hasValue restrictions: restriction class → (property, value), and back.
    has_value: Mapping[Node, tuple[Node, Node]] = field(default_factory=dict)
    restrictions_for: Mapping[tuple[Node, Node], frozenset[Node]] = field(default_factory=dict)
    # Intersection classes: class → members, and member → intersections it takes part in.
    members: Mapping[Node, tuple[Node, ...]] = field(default_factory=dict)
    intersections_with: Mapping[Node, frozenset[Node]] = field(default_factory=dict)

    def schema_closure(self) -> Iterable[Triple]:
        """Inferred subClassOf/subPropertyOf links between named terms (useful to queries)."""
        for cls, sups in self.superclasses.items():
            if isinstance(cls, URIRef):
                for sup in sups:
                    if isinstance(sup, URIRef):
                        yield (cls, RDFS.subClassOf, sup)
        for prop, sups in self.superproperties.items():
            if isinstance(prop, URIRef):
                for sup in sups:
                    if isinstance(sup, URIRef):
                        yield (prop, RDFS.subPropertyOf, sup)


def compile_tbox(triples: Iterable[Triple], bounds: TBoxBounds | None = None) -> CompiledTBox:
    """Build the rule tables from a model's asserted triples (only schema triples are read).
    With ``bounds``, ``TBoxTooLarge`` as soon as the closed hierarchies pass them."""
    class_edges: dict[Node, set[Node]] = defaultdict(set)
    prop_edges: dict[Node, set[Node]] = defaultdict(set)
    domains: dict[Node, set[Node]] = defaultdict(set)
    ranges: dict[Node, set[Node]] = defaultdict(set)
    inverses: dict[Node, set[Node]] = defaultdict(set)
    symmetric: set[Node] = set()
    transitive: set[Node] = set()
    on_property: dict[Node, Node] = {}
    has_value: dict[Node, Node] = {}
    intersection_lists: dict[Node, Node] = {}
    union_lists: dict[Node, Node] = {}
    first: dict[Node, Node] = {}
    rest: dict[Node, Node] = {}

    # What each schema predicate adds, by table: one dict lookup a triple instead of a chain of
    # rdflib term comparisons (a KB compiles the whole ontology whenever it is made).
    linked: dict[Node, tuple[dict[Node, set[Node]], bool]] = {  # (edges, both ways)
        RDFS.subClassOf: (class_edges, False), OWL.equivalentClass: (class_edges, True),
        RDFS.subPropertyOf: (prop_edges, False), OWL.equivalentProperty: (prop_edges, True),
        RDFS.domain: (domains, False), RDFS.range: (ranges, False), OWL.inverseOf: (inverses, True),
    }
    single: dict[Node, dict[Node, Node]] = {
        OWL.onProperty: on_property, OWL.hasValue: has_value, OWL.intersectionOf: intersection_lists,
        OWL.unionOf: union_lists, RDF.first: first, RDF.rest: rest,
    }
    typed: dict[Node, set[Node]] = {OWL.SymmetricProperty: symmetric, OWL.TransitiveProperty: transitive}
    rdf_type = RDF.type
    for s, p, o in triples:
        link = linked.get(p)
        if link is not None:
            edges, both = link
            edges[s].add(o)
            if both:
                edges[o].add(s)
        elif p == rdf_type:
            kind = typed.get(o)
            if kind is not None:
                kind.add(s)
        else:
            value = single.get(p)
            if value is not None:
                value[s] = o

    members: dict[Node, tuple[Node, ...]] = {}
    for cls, head in intersection_lists.items():
        items = _rdf_list(head, first, rest)
        members[cls] = items
        class_edges[cls].update(items)  # C ≡ C1 ⊓ … ⊓ Cn ⇒ C ⊑ Ci (scm-int, cls-int2)
    for cls, head in union_lists.items():
        for item in _rdf_list(head, first, rest):
            class_edges[item].add(cls)  # C ≡ C1 ⊔ … ⊔ Cn ⇒ Ci ⊑ C (scm-uni, cls-uni)

    count = LinkCount(bounds) if bounds is not None else None
    superclasses = _closure(class_edges, TOP_CLASSES, count, "superclasses")
    superproperties = _closure(prop_edges, frozenset(), count, "superproperties")
    restriction_values = {
        r: (on_property[r], v) for r, v in has_value.items() if r in on_property
    }
    restrictions_for: dict[tuple[Node, Node], set[Node]] = defaultdict(set)
    for r, pv in restriction_values.items():
        restrictions_for[pv].add(r)
    intersections_with: dict[Node, set[Node]] = defaultdict(set)
    for cls, items in members.items():
        for item in items:
            intersections_with[item].add(cls)

    return CompiledTBox(
        superclasses=superclasses,
        subclasses=_invert(superclasses),
        superproperties=superproperties,
        subproperties=_invert(superproperties),
        domains=_freeze(domains, drop=TOP_CLASSES),
        ranges=_freeze(ranges, drop=TOP_CLASSES),
        domain_of=_invert(_freeze(domains, drop=TOP_CLASSES)),
        range_of=_invert(_freeze(ranges, drop=TOP_CLASSES)),
        inverses=_freeze(inverses, drop=frozenset()),
        symmetric=frozenset(symmetric),
        transitive=frozenset(transitive),
        has_value=restriction_values,
        restrictions_for={k: frozenset(v) for k, v in restrictions_for.items()},
        members=members,
        intersections_with={k: frozenset(v) for k, v in intersections_with.items()},
    )


def _rdf_list(head: Node, first: Mapping[Node, Node], rest: Mapping[Node, Node]) -> tuple[Node, ...]:
    items: list[Node] = []
    seen: set[Node] = set()
    node = head
    while node != RDF.nil and node in first and node not in seen:
        seen.add(node)
        items.append(first[node])
        node = rest.get(node, RDF.nil)
    return tuple(items)


def _closure(edges: Mapping[Node, set[Node]], drop: frozenset[Node], count: LinkCount | None,
             kind: str) -> dict[Node, frozenset[Node]]:
    """Reflexive-free transitive closure of a relation given as adjacency sets, counted against
    the bounds as it is made (the start and what is dropped count too: a bound a little early)."""
    result: dict[Node, frozenset[Node]] = {}
    depth = count.bounds.max_depth + len(drop) + 1 if count is not None else None
    for start in edges:
        seen: set[Node] = set()
        stack = list(edges[start])
        while stack:
            node = stack.pop()
            if node in seen:
                continue
            seen.add(node)
            if depth is not None and len(seen) > depth:
                assert count is not None
                count.add(start, len(seen), kind)
            stack.extend(edges.get(node, ()))
        seen.discard(start)
        seen -= drop
        seen = {n for n in seen if not isinstance(n, Literal)}
        if seen:
            result[start] = frozenset(seen)
            if count is not None:
                count.add(start, len(seen), kind)
    return result


def _invert(table: Mapping[Node, frozenset[Node]]) -> dict[Node, frozenset[Node]]:
    inverted: dict[Node, set[Node]] = defaultdict(set)
    for key, values in table.items():
        for value in values:
            inverted[value].add(key)
    return {k: frozenset(v) for k, v in inverted.items()}


def _freeze(table: Mapping[Node, set[Node]], drop: frozenset[Node]) -> dict[Node, frozenset[Node]]:
    return {k: frozenset(v - drop) for k, v in table.items() if v - drop}


def is_blank(term: Node) -> bool:
    return isinstance(term, BNode)
