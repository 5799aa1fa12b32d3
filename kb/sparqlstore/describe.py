"""details, about, label, classesof and lookup of a read replica: the term's neighbourhood fetched
from the store in one or two requests, described by kb.describe.

Each call fetches the triples kb.describe reads about the term (with the graph each comes from,
so asserted and inferred stay apart) into small local ``TripleIndex`` objects, one closure subset
and one asserted subset per model, and runs the unchanged kb.describe functions on them: the
answers are those of the in-process KB by construction. Several models are fetched in the same
request, each triple tagged with its graph.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

from rdflib import BNode, Literal, URIRef, Variable
from rdflib.namespace import RDF, RDFS

from kb import describe
from kb.index import TripleIndex
from kb.sparqlstore import text
from kb.sparqlstore.endpoint import SparqlEndpoint
from kb.sparqlstore.query import Graphs
from kb.tbox import TOP_CLASSES
from kb.terms import PREFIXES, Node, Pattern, shorten

_G, _S, _P, _O, _T = (Variable(v) for v in ("g", "s", "p", "o", "t"))
_X, _Y, _N = Variable("x"), Variable("y"), Variable("n")
_CLASS_LINKS = f"({text.term(RDF.type)}|{text.term(RDFS.subClassOf)})"
# The terms kb.reasoner may write into a closure without their being in any asserted triple.
REASONER_TERMS = frozenset({RDF.type, RDFS.subClassOf, RDFS.subPropertyOf, *TOP_CLASSES})


def _bind(var: Variable, node: Node) -> str:
    return f"BIND({text.term(node)} AS {text.term(var)})"


def _tagged(graph: URIRef, patterns: Sequence[Pattern], *binds: tuple[Variable, Node],
            where: str = "") -> str:
    """A UNION branch: the patterns in one graph, the graph and the fixed positions bound."""
    bound = " ".join(_bind(var, node) for var, node in ((_G, graph), *binds))
    return f"{{ GRAPH {text.term(graph)} {{ {text.block(patterns)} {where} }} {bound} }}"


def _select(branches: Sequence[str], projection: str = "?g ?s ?p ?o") -> str:
    return f"SELECT DISTINCT {projection} WHERE {{\n" + "\nUNION\n".join(branches) + "\n}"


def _edges(term: Node, graph: URIRef) -> list[str]:
    """Triples of one graph where the term is the subject, the predicate or the object."""
    branches = [_tagged(graph, [(_S, _P, term)], (_O, term))]
    if not isinstance(term, Literal):
        branches.append(_tagged(graph, [(term, _P, _O)], (_S, term)))
        branches.append(_tagged(graph, [(_S, term, _O)], (_P, term)))
    return branches


def details_text(term: Node, graphs: Graphs) -> str:
    """What describe.details reads: every triple around the term, except the inferred
    ``rdf:type`` / ``rdfs:subClassOf`` triples pointing at it (instances and subclasses come from
    the asserted graph; of the inferred ones only one each, for the term's kind), plus the labels
    of the classes, parents, children and instances it lists."""
    a, i = graphs.asserted, graphs.inferred
    if isinstance(term, Literal):
        return _select([b for g in (a, i) for b in _edges(term, g)])
    hidden = f"FILTER ({text.term(_P)} NOT IN ({text.term(RDF.type)}, {text.term(RDFS.subClassOf)}))"
    branches = [
        _tagged(a, [(_S, _P, term)], (_O, term)),
        _tagged(i, [(_S, _P, term)], (_O, term), where=hidden),
    ]
    for g in (a, i):
        branches.append(_tagged(g, [(term, _P, _O)], (_S, term)))
        branches.append(_tagged(g, [(_S, term, _O)], (_P, term)))
    for link in (RDF.type, RDFS.subClassOf):
        one = f"{{ SELECT ?s WHERE {{ GRAPH {text.term(i)} {{ {text.triple(_S, link, term)} }} }} LIMIT 1 }}"
        branches.append(f"{{ {one} {_bind(_G, i)} {_bind(_P, link)} {_bind(_O, term)} }}")
    t, n = text.term(term), text.term(_N)
    neighbours = " UNION ".join([
        f"{{ GRAPH {text.term(a)} {{ {t} {_CLASS_LINKS} {n} }} }}",
        f"{{ GRAPH {text.term(i)} {{ {t} {_CLASS_LINKS} {n} }} }}",
        f"{{ GRAPH {text.term(a)} {{ {n} {_CLASS_LINKS} {t} }} }}",
    ])
    labels = " UNION ".join(_tagged(g, [(_N, RDFS.label, _O)]) for g in (a, i))
    branches.append(f"{{ {neighbours} {labels} BIND({n} AS ?s) {_bind(_P, RDFS.label)} }}")
    return _select(branches)


def about_text(term: Node | None, raw: str, models: Sequence[Graphs]) -> str:
    """What describe.about reads: the triples around the term and the labels containing ``raw``."""
    contains = f"FILTER (isLiteral(?o) && CONTAINS(STR(?o), {text.term(Literal(raw))}))"
    branches = []
    for graphs in models:
        for g in graphs.closure():
            if term is not None:
                branches.extend(_edges(term, g))
            branches.append(_tagged(g, [(_S, RDFS.label, _O)], (_P, RDFS.label), where=contains))
    return _select(branches)


def objects_text(term: Node, predicate: URIRef, models: Sequence[Graphs], inferred: bool = True) -> str:
    """The term's values of one predicate (labels, classes), from every given model."""
    return _select([_tagged(g, [(term, predicate, _O)], (_S, term), (_P, predicate))
                    for graphs in models for g in graphs.closure(inferred)])


def lookup_text(query: str, models: Sequence[Graphs]) -> str:
    """Names and literals that may match ``query`` (a superset: the exact test is
    describe.lookup's): IRIs whose text or shortened form holds it, case-insensitively, and every
    triple whose literal object holds it.

    Only the asserted graph is scanned for terms: the reasoner derives triples between terms it
    was given (asserted ones, the ontology included) and writes no others except the few of
    REASONER_TERMS, which are looked for in the inferred graph by name. The triples of the
    matching literals then come from both graphs, found by the literal (test_remotedescribe.py
    checks that invariant of kb.reasoner)."""
    needle = query.lower()
    n = text.term(Literal(needle))
    names = [f"CONTAINS(LCASE(STR(?t)), {n})"]
    for prefix, namespace in PREFIXES.items():
        label = f"{prefix}:"
        # A shortened name "prefix:local" holds the needle without the IRI holding it only when
        # the needle runs into the "prefix:" part.
        if prefix and _overlaps(label.lower(), needle):
            ns, short = text.term(Literal(namespace)), text.term(Literal(label))
            names.append(f"(STRSTARTS(STR(?t), {ns}) && "
                         f"CONTAINS(LCASE(CONCAT({short}, STRAFTER(STR(?t), {ns}))), {n}))")
    name_filter = f"FILTER (isIRI(?t) && ({' || '.join(names)}))"
    positions = " UNION ".join(f"{{ {text.triple(*p)} }}" for p in ((_T, _X, _Y), (_X, _T, _Y), (_X, _Y, _T)))
    reasoner_terms = text.values(_T, sorted(REASONER_TERMS))
    branches = []
    for graphs in models:
        a, i = text.term(graphs.asserted), text.term(graphs.inferred)
        branches.append(f"{{ GRAPH {a} {{ {positions} }} {name_filter} {_bind(_G, graphs.asserted)} }}")
        branches.append(f"{{ {reasoner_terms} {name_filter} FILTER EXISTS {{ GRAPH {i} {{ {positions} }} }} "
                        f"{_bind(_G, graphs.inferred)} }}")
        literals = (f"{{ SELECT DISTINCT ?o WHERE {{ GRAPH {a} {{ ?x ?y ?o }} "
                    f"FILTER (isLiteral(?o) && CONTAINS(LCASE(STR(?o)), {n})) }} }}")
        in_either = " UNION ".join(_tagged(g, [(_S, _P, _O)]) for g in graphs.closure())
        branches.append(f"{{ {literals} {in_either} }}")
    return _select(branches, "?g ?t ?s ?p ?o")


def _overlaps(label: str, needle: str) -> bool:
    return needle in label or any(label.endswith(needle[:k])
                                  for k in range(1, min(len(label), len(needle)) + 1))


def kinds_text(pairs: Sequence[tuple[Graphs, URIRef]]) -> str:
    """What describe.term_kind reads about each (model, term): the term's classes, and whether it
    has instances, subclasses, superclasses, and triples as a predicate (with a literal object).
    The predicate facts are only looked for when the term has no class (term_kind decides from
    the classes first): for a property with many triples they may cost a scan."""
    by_model: dict[Graphs, list[URIRef]] = {}
    for graphs, term in pairs:
        by_model.setdefault(graphs, []).append(term)
    branches = []
    for graphs, terms in by_model.items():
        a, i = text.term(graphs.asserted), text.term(graphs.inferred)
        hits = text.values(Variable("h"), terms)

        def either(pattern: str, a: str = a, i: str = i) -> str:
            return f"{{ GRAPH {a} {{ {pattern} }} }} UNION {{ GRAPH {i} {{ {pattern} }} }}"

        rdf_type, sub_class = text.term(RDF.type), text.term(RDFS.subClassOf)
        branches.append(f"{{ {hits} {either(f'?h {rdf_type} ?c')} BIND({a} AS ?a) }}")
        branches.append(
            f"{{ {hits} BIND({a} AS ?a)\n"
            f"BIND (EXISTS {{ {either(f'?h {rdf_type} ?x')} }} AS ?typed)\n"
            f"BIND (EXISTS {{ {either(f'?x {rdf_type} ?h')} }} AS ?inst)\n"
            f"BIND (EXISTS {{ {either(f'?x {sub_class} ?h')} }} AS ?sub)\n"
            f"BIND (EXISTS {{ {either(f'?h {sub_class} ?x')} }} AS ?sup)\n"
            f"BIND (IF(?typed, false, EXISTS {{ {either('?x ?h ?y')} }}) AS ?pred)\n"
            f"BIND (IF(?pred, EXISTS {{ {either('?x ?h ?y FILTER (isLiteral(?y))')} }}, false) AS ?lit) }}")
    return _select(branches, "?a ?h ?c ?inst ?sub ?sup ?pred ?lit")


class Neighbourhood:
    """Fetched triples of some models, as a closure subset and an asserted subset per model."""

    def __init__(self, models: Sequence[Graphs]) -> None:
        self.closure = {g.model: TripleIndex() for g in models}
        self.asserted = {g.model: TripleIndex() for g in models}
        self._graphs = {g.asserted: (g.model, True) for g in models}
        self._graphs.update({g.inferred: (g.model, False) for g in models})

    def add(self, rows: Iterable[dict[str, Node]]) -> Neighbourhood:
        for row in rows:
            model, asserted = self._graphs[row["g"]]  # type: ignore[index]
            s, p, o = row["s"], row["p"], row["o"]
            self.closure[model].add(s, p, o)
            if asserted:
                self.asserted[model].add(s, p, o)
        return self


class StoreDescriber:
    """The describe calls answered from a store; one request each, two for lookup."""

    def __init__(self, endpoint: SparqlEndpoint) -> None:
        self.endpoint = endpoint

    def _fetch(self, query: str, models: Sequence[Graphs]) -> Neighbourhood:
        return Neighbourhood(models).add(self.endpoint.select(query))

    def details(self, term: Node, graphs: Graphs, origin: bool) -> dict[str, Any]:
        near = self._fetch(details_text(term, graphs), [graphs])
        return describe.details(near.closure[graphs.model], near.asserted[graphs.model], term, origin)

    def about(self, term: Node | None, raw: str, models: Sequence[Graphs]) -> list[list[Any]]:
        near = self._fetch(about_text(term, raw, models), models)
        found: list[list[Any]] = []
        for graphs in models:
            closure = near.closure[graphs.model]
            found.extend(st for st in describe.about(closure, term, raw) if st not in found)
        return found

    def label(self, term: Node, lang: str | None, graphs: Graphs) -> str:
        if isinstance(term, Literal):  # a literal has no label: describe answers from the term itself
            return describe.label(TripleIndex(), term, lang)
        near = self._fetch(objects_text(term, RDFS.label, [graphs]), [graphs])
        return describe.label(near.closure[graphs.model], term, lang)

    def classes_of(self, term: Node, direct: bool, models: Sequence[Graphs]) -> list[str]:
        found: set[str] = set()
        if isinstance(term, Literal):
            return []
        near = self._fetch(objects_text(term, RDF.type, models, inferred=not direct), models)
        for graphs in models:
            model = graphs.model
            found.update(describe.classes_of(near.closure[model], near.asserted[model], term, direct))
        return sorted(found)

    def lookup(self, query: str, models: Sequence[Graphs]) -> list[list[Any]]:
        """kb-compat §3.4, merged over models as KB.lookup merges them."""
        candidates = self._candidates(query, models)
        found = describe.merged((g, *describe.lookup(candidates[g.model], query)) for g in models)
        kinds = self._kinds([(g, t) for t, g in found])
        return [[str(shorten(t)), kinds[g.model, t]] for t, g in found]

    def _candidates(self, query: str, models: Sequence[Graphs]) -> dict[str, TripleIndex]:
        near = Neighbourhood(models)
        # A blank-node edge makes a name known to describe.lookup (which lists IRIs only) without
        # inventing a triple between names.
        mark = BNode()
        rows = self.endpoint.select(lookup_text(query, models))
        near.add({"g": r["g"], "s": r["t"], "p": mark, "o": mark} if "t" in r else r for r in rows)
        return near.closure

    def _kinds(self, pairs: Sequence[tuple[Graphs, Node]]) -> dict[tuple[str, Node], str]:
        kinds: dict[tuple[str, Node], str] = {
            (g.model, t): "literal" for g, t in pairs if isinstance(t, Literal)}
        names = [(g, t) for g, t in pairs if isinstance(t, URIRef)]
        if not names:
            return kinds
        graphs = {g.asserted: g for g, _ in names}
        facts: dict[tuple[str, Node], TripleIndex] = {}
        for row in self.endpoint.select(kinds_text(names)):
            model, term = graphs[row["a"]].model, row["h"]  # type: ignore[index]
            index = facts.setdefault((model, term), TripleIndex())
            if "c" in row:
                index.add(term, RDF.type, row["c"])
            else:
                _add_kind_facts(index, term, row)
        for (model, term), index in facts.items():
            kinds[model, term] = describe.term_kind(index, term)
        return kinds


def _add_kind_facts(index: TripleIndex, term: Node, flags: dict[str, Node]) -> None:
    """The facts describe.term_kind reads, with a blank node for "some term": it asks whether
    such triples exist, never which terms they hold."""

    def holds(name: str) -> bool:
        value = flags.get(name)
        return isinstance(value, Literal) and value.toPython() is True

    if holds("inst"):
        index.add(BNode(), RDF.type, term)
    if holds("sub"):
        index.add(BNode(), RDFS.subClassOf, term)
    if holds("sup"):
        index.add(term, RDFS.subClassOf, BNode())
    if holds("pred"):
        # describe.term_kind looks at one object of a predicate; when it has objects of both
        # kinds, the in-process KB answers by insertion order, which the store does not keep:
        # here, any literal object makes a datatype property.
        index.add(BNode(), term, Literal("") if holds("lit") else BNode())
