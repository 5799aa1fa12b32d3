"""What the KB says about one term: details, labels, classes, lookup and about (kb-compat §3.3–3.4)."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any, TypeVar

from rdflib import BNode, Literal, URIRef
from rdflib.namespace import OWL, RDF, RDFS

from kb.index import TripleIndex
from kb.terms import ORO, Node, Triple, Value, shorten, shorten_iri

ACTIVE_CONCEPT = URIRef(ORO + "ActiveConcept")
OPEN_CYC_URI = URIRef(ORO + "openCycUri")
HIDDEN_CLASSES = frozenset({OWL.Thing, RDFS.Resource, OWL.NamedIndividual, ACTIVE_CONCEPT})
# Predicates left out of details()["relations"] when the term is subject or object (§3.3).
HIDDEN_RELATIONS = frozenset(
    {
        RDF.type, RDFS.subClassOf, RDFS.label, RDFS.comment, RDFS.domain, RDFS.range,
        OWL.disjointWith, RDF.first, OPEN_CYC_URI,
    }
)
CLASS_TYPES = frozenset({OWL.Class, RDFS.Class})

Statement = list[Value]


def term_kind(index: TripleIndex, term: Node) -> str:
    """knowledge_core's term type, decided in the order of kb-compat §3.3."""
    if isinstance(term, Literal):
        return "literal"
    types = index.objects(term, RDF.type)
    if OWL.ObjectProperty in types:
        return "object_property"
    if OWL.DatatypeProperty in types:
        return "datatype_property"
    if types & CLASS_TYPES:
        return "class"
    if types:
        return "instance"
    if (
        index.has_predicate_object(RDF.type, term)
        or index.has_predicate_object(RDFS.subClassOf, term)
        or index.has_subject_predicate(term, RDFS.subClassOf)
    ):
        return "class"
    if index.is_predicate(term):
        first = next(iter(index.by_predicate(term)), None)
        return "datatype_property" if isinstance(first, Literal) else "object_property"
    return "undecided"


def label_dict(index: TripleIndex, term: Node) -> dict[str, str]:
    """Labels by language, untagged under ``default``; ``default`` falls back to ``en``, then
    to the shortened term. Several labels in one language: the alphabetically first, so the
    answer never depends on set order."""
    return _label_dict(term, index.objects(term, RDFS.label))


def _label_dict(term: Node, objects: Iterable[Node]) -> dict[str, str]:
    """`label_dict` of a term whose ``rdfs:label`` objects are ``objects``."""
    labels: dict[str, str] = {}
    for lit in sorted(objects, key=str):
        if isinstance(lit, Literal):
            labels.setdefault(lit.language or "default", str(lit))
    if "default" not in labels:
        labels["default"] = labels.get("en") or str(shorten(term) if not isinstance(term, BNode) else term)
    return labels


def label(index: TripleIndex, term: Node, lang: str | None = None) -> str:
    return _chosen(label_dict(index, term), lang)


def _chosen(labels: dict[str, str], lang: str | None) -> str:
    """The label of ``labels`` (`label_dict`) in ``lang``, else the default one."""
    if lang:
        for key in (lang, lang.split("-")[0].split("_")[0]):
            if key in labels:
                return labels[key]
    return labels["default"]


def _values(index: TripleIndex, terms: Iterable[Node], with_name: bool = False) -> list[dict[str, Any]]:
    values = []
    for term in sorted((t for t in terms if isinstance(t, URIRef)), key=shorten_iri):
        labels = label_dict(index, term)
        value: dict[str, Any] = {"id": shorten_iri(str(term)), "label": labels}
        if with_name:
            value["name"] = labels  # upstream's key for Parents, kept for old viewers (K10)
        values.append(value)
    return values


def details(closure: TripleIndex, asserted: TripleIndex, term: Node, origin: bool = False) -> dict[str, Any]:
    kind = term_kind(closure, term)
    attributes: list[dict[str, Any]] = []
    if kind == "instance":
        classes = asserted.objects(term, RDF.type) - HIDDEN_CLASSES
        if not classes:
            classes = closure.objects(term, RDF.type) - HIDDEN_CLASSES
        attributes = [{"name": "Classes", "id": "classes", "values": _values(closure, classes)}]
    elif kind == "class":
        parents = asserted.objects(term, RDFS.subClassOf) - HIDDEN_CLASSES
        children = asserted.subjects(RDFS.subClassOf, term)
        instances = asserted.subjects(RDF.type, term)
        attributes = [
            {"name": "Parents", "id": "superClasses", "values": _values(closure, parents, with_name=True)},
            {"name": "Children", "id": "subClasses", "values": _values(closure, children)},
            {"name": "Instances", "id": "instances", "values": _values(closure, instances)},
        ]
    found = relation_triples(closure, term)
    result: dict[str, Any] = {
        "id": shorten(term),
        "label": label_dict(closure, term),
        "type": kind,
        "attributes": attributes,
        "relations": statements(found),
    }
    if origin:
        # One flag per relation, in the same order: asserted (True) or only inferred (False).
        ordered = sorted(_visible(found), key=lambda t: tuple(str(v) for v in _short(t)))
        result["asserted"] = [t in asserted for t in ordered]
    return result


def relations(closure: TripleIndex, term: Node) -> list[Statement]:
    return statements(relation_triples(closure, term))


def relation_triples(closure: TripleIndex, term: Node) -> set[Triple]:
    found: set[Triple] = set()
    for p, objs in closure.out_edges(term).items():
        if p not in HIDDEN_RELATIONS:
            found.update((term, p, o) for o in objs)
    for s, preds in closure.in_edges(term).items():
        found.update((s, p, term) for p in preds if p not in HIDDEN_RELATIONS)
    for o, subjects in closure.by_predicate(term).items():
        found.update((s, term, o) for s in subjects)
    return found


def _visible(triples: Iterable[Triple]) -> list[Triple]:
    """Triples that may appear in results: no blank nodes, literal subjects or ``x sameAs x``."""
    return [
        (s, p, o) for s, p, o in triples
        if not isinstance(s, BNode | Literal) and not isinstance(o, BNode)
        and not (p == OWL.sameAs and s == o)
    ]


def _short(triple: Triple) -> Statement:
    return [v for v in (shorten(t) for t in triple) if v is not None]


def statements(triples: Iterable[Triple]) -> list[Statement]:
    """Triples as sorted ``[s, p, o]`` lists of output values, blank nodes left out (K11)."""
    out = [_short(t) for t in _visible(triples)]
    out.sort(key=lambda st: tuple(str(v) for v in st))
    return out


def classes_of(closure: TripleIndex, asserted: TripleIndex, term: Node, direct: bool) -> list[str]:
    source = asserted if direct else closure
    return sorted(
        shorten_iri(str(c)) for c in source.objects(term, RDF.type) - HIDDEN_CLASSES if isinstance(c, URIRef)
    )


def all_classes(closure: TripleIndex, asserted: TripleIndex, direct: bool) -> dict[str, list[str]]:
    """``classes_of`` of every term that has a class, read class by class (one pass, no per-term
    lookup): what a snapshot of the whole KB asks."""
    found: dict[Node, list[str]] = {}
    for klass, members in (asserted if direct else closure).by_predicate(RDF.type).items():
        if not isinstance(klass, URIRef) or klass in HIDDEN_CLASSES:
            continue
        name = shorten_iri(str(klass))
        for member in members:
            found.setdefault(member, []).append(name)
    named = {short: classes for member, classes in found.items() if isinstance(short := shorten(member), str)}
    for classes in named.values():  # (blank nodes never appear in answers)
        classes.sort()
    return named


def all_labels(closure: TripleIndex, lang: str | None) -> dict[str, str]:
    """``label`` of every term that has an ``rdfs:label``, in one pass over the labels (each term's
    labels gathered from it, not looked up again term by term: a tenth of a first snapshot)."""
    by_subject: dict[Node, list[Node]] = {}
    for lit, subjects in closure.by_predicate(RDFS.label).items():
        for subject in subjects:
            by_subject.setdefault(subject, []).append(lit)
    found: dict[str, str] = {}
    for subject, objects in by_subject.items():
        short = shorten(subject)
        if isinstance(short, str):
            found[short] = _chosen(_label_dict(subject, objects), lang)
    return found


def about(closure: TripleIndex, term: Node | None, raw: str) -> list[Statement]:
    found: set[Triple] = set()
    if term is not None:
        found.update(closure.triples(term, None, None))
        found.update(closure.triples(None, term, None))
        found.update(closure.triples(None, None, term))
    for lit, subjects in closure.by_predicate(RDFS.label).items():
        if isinstance(lit, Literal) and raw in str(lit):
            found.update((s, RDFS.label, lit) for s in subjects)
    return statements(found)


def lookup(closure: TripleIndex, query: str) -> tuple[list[Node], list[Node]]:
    """Terms matching ``query`` exactly, then approximately (case-insensitive substring)."""
    exact: set[Node] = set()
    approx: set[Node] = set()
    needle = query.lower()

    def match(text: str, hit: Node) -> None:
        if text == query:
            exact.add(hit)
        elif needle in text.lower():
            approx.add(hit)

    for term in _names(closure):
        match(shorten_iri(str(term)), term)
    for obj in list(closure.object_terms()):
        if not isinstance(obj, Literal):
            continue
        text = str(obj)
        if needle not in text.lower():
            continue
        for subj, preds in closure.in_edges(obj).items():
            for p in preds:
                match(text, subj if p == RDFS.label else obj)
    exact -= HIDDEN_CLASSES
    exact -= {t for t in exact if isinstance(t, BNode)}
    approx -= HIDDEN_CLASSES | exact
    approx -= {t for t in approx if isinstance(t, BNode)}
    key = sort_key
    return sorted(exact, key=key), sorted(approx, key=key)


def _names(closure: TripleIndex) -> set[Node]:
    names: set[Node] = set()
    for terms in (closure.subject_terms(), closure.predicate_terms(), closure.object_terms()):
        names.update(t for t in terms if isinstance(t, URIRef))
    return names


def sort_key(term: Node) -> tuple[int, str]:
    """The order of lookup's answers: names before literals, then by text."""
    return (1 if isinstance(term, Literal) else 0, str(shorten(term)))


M = TypeVar("M")


def merged(found: Iterable[tuple[M, list[Node], list[Node]]]) -> list[tuple[Node, M]]:
    """``lookup`` over several models (each ``(model, exact, approximate)``): exact matches first,
    then approximate ones that are exact nowhere, each with the first model that has it."""
    exact: dict[Node, M] = {}
    approx: dict[Node, M] = {}
    for model, e, a in found:
        for t in e:
            exact.setdefault(t, model)
        for t in a:
            approx.setdefault(t, model)
    for t in exact:
        approx.pop(t, None)
    return [(t, exact[t]) for t in sorted(exact, key=sort_key)] + [
        (t, approx[t]) for t in sorted(approx, key=sort_key)
    ]
