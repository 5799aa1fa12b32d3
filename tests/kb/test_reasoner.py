"""The incremental reasoner against owlrl, the reference semantics (kb-compat §7.4–7.5).

Random add/retract sequences are applied incrementally (semi-naive insertion, DRed deletion);
the closure must equal a from-scratch materialisation after every step, and owlrl's OWL RL
closure of the asserted triples, noise filtered, at the end.
"""

from __future__ import annotations

import random
from collections.abc import Iterable
from importlib.resources import files
from pathlib import Path

import owlrl
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from rdflib import BNode, Graph, Literal, URIRef
from rdflib.namespace import OWL, RDF, RDFS, XSD

from kb.models import Model
from kb.rdfio import parse_data
from kb.terms import ORO, Triple

NOISE_NAMESPACES = (str(OWL), str(RDF), str(RDFS), str(XSD))
MINI = parse_data((Path(__file__).parent / "data" / "mini.ttl").read_text(), "turtle")


def oro(name: str) -> URIRef:
    return URIRef(ORO + name)


def abox(triples: Iterable[Triple]) -> set[Triple]:
    """The ABox projection with owlrl's noise removed: no blank nodes, no literal subjects,
    no sameAs/vocabulary triples, no typing by RDF/RDFS/OWL classes."""
    kept = set()
    for s, p, o in triples:
        if isinstance(s, BNode | Literal) or isinstance(o, BNode):
            continue
        if p == RDF.type:
            if str(o).startswith(NOISE_NAMESPACES):
                continue
        elif str(p).startswith(NOISE_NAMESPACES):
            continue
        kept.add((s, p, o))
    return kept


def owlrl_closure(triples: Iterable[Triple]) -> set[Triple]:
    graph = Graph()
    for t in triples:
        graph.add(t)
    owlrl.DeductiveClosure(owlrl.OWLRL_Semantics, axiomatic_triples=False).expand(graph)
    return abox(graph)  # type: ignore[arg-type]


INDIVIDUALS = [oro(n) for n in ("a", "b", "c", "d")]
CLASSES = [oro(n) for n in ("Human", "Robot", "Person", "Table", "Cup", "Furniture", "Located", "Red")]
OBJECT_PROPERTIES = [
    oro(n) for n in ("sees", "looksAt", "isAt", "isOn", "isIn", "placeOf", "isNextTo", "leftOf",
                     "rightOf", "knows")
]
COLOURS = [oro("red"), oro("blue")]

fact = st.one_of(
    st.tuples(st.sampled_from(INDIVIDUALS), st.just(RDF.type), st.sampled_from(CLASSES)),
    st.tuples(st.sampled_from(INDIVIDUALS), st.sampled_from(OBJECT_PROPERTIES), st.sampled_from(INDIVIDUALS)),
    st.tuples(st.sampled_from(INDIVIDUALS), st.sampled_from([oro("hasColor"), oro("colour")]),
              st.sampled_from(COLOURS)),
    st.tuples(st.sampled_from(INDIVIDUALS), st.sampled_from([oro("isHolder"), oro("isMovable")]),
              st.sampled_from([Literal(True), Literal(False)])),
)
operation = st.tuples(st.sampled_from(["add", "add", "remove"]), fact)


def scratch(model: Model) -> set[Triple]:
    return set(Model("scratch", list(model.asserted)).closure)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(operation, min_size=1, max_size=25))
def test_incremental_closure_matches_scratch_and_owlrl(ops: list[tuple[str, Triple]]) -> None:
    model = Model("default", MINI)
    asserted_abox: list[Triple] = []
    for op, triple in ops:
        if op == "add":
            model.apply([triple], [])
            asserted_abox.append(triple)
        else:
            # Retract something that is asserted most of the time, or a random fact otherwise.
            target = asserted_abox[-1] if asserted_abox and triple[1] == RDF.type else triple
            model.apply([], [target])
            asserted_abox = [t for t in asserted_abox if t != target]
        assert set(model.closure) == scratch(model)
    assert abox(model.closure) == owlrl_closure(model.asserted)


def test_delta_reports_exactly_what_changed() -> None:
    model = Model("default", MINI)
    before = set(model.closure)
    delta = model.apply([(oro("c1"), RDF.type, oro("Cup")), (oro("c1"), oro("isOn"), oro("t1"))], [])
    middle = set(model.closure)
    assert set(delta.added) == middle - before and not delta.removed
    delta = model.apply([], [(oro("c1"), oro("isOn"), oro("t1"))])
    after = set(model.closure)
    assert set(delta.removed) == middle - after and not delta.added
    assert (oro("t1"), oro("placeOf"), oro("c1")) in delta.removed
    assert (oro("c1"), oro("isMovable"), Literal(True)) in after


def test_fact_with_two_supports_survives_losing_one() -> None:
    model = Model("default", MINI)
    model.apply([(oro("x"), oro("isOn"), oro("y")), (oro("x"), oro("isIn"), oro("y"))], [])
    model.apply([], [(oro("x"), oro("isOn"), oro("y"))])
    assert (oro("x"), oro("isAt"), oro("y")) in model.closure
    assert (oro("y"), oro("placeOf"), oro("x")) in model.closure
    model.apply([], [(oro("x"), oro("isIn"), oro("y"))])
    assert (oro("x"), oro("isAt"), oro("y")) not in model.closure


def test_transitive_chain_is_cut_in_the_middle() -> None:
    model = Model("default", MINI)
    chain = [(oro(f"n{i}"), oro("leftOf"), oro(f"n{i + 1}")) for i in range(6)]
    model.apply(chain, [])
    assert (oro("n0"), oro("leftOf"), oro("n6")) in model.closure
    assert (oro("n6"), oro("rightOf"), oro("n0")) in model.closure
    model.apply([], [chain[3]])
    assert (oro("n0"), oro("leftOf"), oro("n3")) in model.closure
    assert (oro("n0"), oro("leftOf"), oro("n4")) not in model.closure
    assert set(model.closure) == scratch(model)


def test_tbox_change_recompiles_and_rematerialises() -> None:
    model = Model("default", MINI)
    model.apply([(oro("m1"), RDF.type, oro("Mug"))], [])
    assert (oro("m1"), RDF.type, oro("Artifact")) not in model.closure
    delta = model.apply([(oro("Mug"), RDFS.subClassOf, oro("Cup"))], [])
    assert (oro("m1"), RDF.type, oro("Artifact")) in model.closure
    assert (oro("m1"), RDF.type, oro("Artifact")) in delta.added
    assert (oro("Mug"), RDFS.subClassOf, oro("Artifact")) in model.closure  # schema closure
    delta = model.apply([], [(oro("Mug"), RDFS.subClassOf, oro("Cup"))])
    assert (oro("m1"), RDF.type, oro("Artifact")) in delta.removed


@pytest.fixture(scope="module")
def oro_ontology() -> tuple[Triple, ...]:
    data = (files("ontologies") / "oro.ttl").read_text(encoding="utf-8")
    return parse_data(data, "turtle")


def test_oro_ontology_random_ticks_match_owlrl(oro_ontology: tuple[Triple, ...]) -> None:
    """A perception-like sequence on the real ontology; owlrl checked once at the end (it
    takes seconds on ORO, which is why the KB does not use it on the hot path)."""
    rng = random.Random(7)
    classes = ["dbr:Cup", "dbr:Book", "dbr:Apple", "dbr:Table_(furniture)", "dbr:Couch", "Human", "Robot",
               "ZoneOfInterest", "dbr:Shelf_(storage)", "dbr:Smartphone"]
    predicates = ["sees", "looksAt", "isIn", "isOn", "isNextTo", "leftOf", "focusesOn", "hasInHand"]
    things = [oro(f"thing_{i}") for i in range(12)]
    model = Model("default", oro_ontology)
    live: list[Triple] = []
    from kb.terms import parse_ground

    for thing in things:
        cls = parse_ground(f"x rdf:type {rng.choice(classes)}")[2]
        model.apply([(thing, RDF.type, cls)], [])
    for _ in range(120):
        if live and rng.random() < 0.4:
            gone = live.pop(rng.randrange(len(live)))
            model.apply([], [gone])
        else:
            new = (rng.choice(things), oro(rng.choice(predicates)), rng.choice(things))
            model.apply([new], [])
            live.append(new)
    assert set(model.closure) == scratch(model)
    assert abox(model.closure) == owlrl_closure(model.asserted)
