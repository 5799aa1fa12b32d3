"""Models (kb-compat §2, §7.5): asserted triples kept apart from the closure, deltas, TBox
recompilation, new models from the default TBox (K15), and reset for clear (K5).
"""

from __future__ import annotations

from rdflib import Namespace, URIRef

from kb.models import DEFAULT_MODEL, Model, Models
from kb.rdfio import default_ontology
from kb.terms import Triple

EX = Namespace("http://kb.openrobots.org#")
RDF = Namespace("http://www.w3.org/1999/02/22-rdf-syntax-ns#")
RDFS = Namespace("http://www.w3.org/2000/01/rdf-schema#")
OWL = Namespace("http://www.w3.org/2002/07/owl#")
TYPE = RDF.type

TBOX: list[Triple] = [
    (EX.Cat, RDFS.subClassOf, EX.Animal),
    (EX.Animal, RDFS.subClassOf, EX.Thing2),
    (EX.owns, RDFS.range, EX.Possession),
    (EX.owns, OWL.inverseOf, EX.ownedBy),
]


def test_asserted_and_closure_are_kept_apart() -> None:
    model = Model("m", TBOX)
    delta = model.apply([(EX.tom, TYPE, EX.Cat)], [])
    assert delta.model == "m"
    assert delta.asserted_added == [(EX.tom, TYPE, EX.Cat)]
    assert delta.asserted_removed == []
    assert set(delta.added) >= {(EX.tom, TYPE, EX.Cat), (EX.tom, TYPE, EX.Animal), (EX.tom, TYPE, EX.Thing2)}
    assert (EX.tom, TYPE, EX.Animal) in model.closure
    assert (EX.tom, TYPE, EX.Animal) not in model.asserted
    assert model.is_asserted((EX.tom, TYPE, EX.Cat))
    assert not model.is_asserted((EX.tom, TYPE, EX.Animal))


def test_no_change_gives_an_empty_delta() -> None:
    model = Model("m", TBOX)
    model.apply([(EX.tom, TYPE, EX.Cat)], [])
    again = model.apply([(EX.tom, TYPE, EX.Cat)], [(EX.nobody, TYPE, EX.Cat)])
    assert not again
    assert again.added == [] and again.removed == []


def test_retract_removes_derived_facts() -> None:
    model = Model("m", TBOX)
    model.apply([(EX.tom, EX.owns, EX.ball)], [])
    assert (EX.ball, EX.ownedBy, EX.tom) in model.closure
    assert (EX.ball, TYPE, EX.Possession) in model.closure
    delta = model.apply([], [(EX.tom, EX.owns, EX.ball)])
    assert delta.asserted_removed == [(EX.tom, EX.owns, EX.ball)]
    assert {(EX.ball, EX.ownedBy, EX.tom), (EX.ball, TYPE, EX.Possession)} <= set(delta.removed)
    assert (EX.ball, EX.ownedBy, EX.tom) not in model.closure


def test_retract_keeps_facts_with_another_support() -> None:
    model = Model("m", TBOX)
    model.apply([(EX.tom, EX.owns, EX.ball), (EX.ann, EX.owns, EX.ball)], [])
    delta = model.apply([], [(EX.tom, EX.owns, EX.ball)])
    assert (EX.ball, TYPE, EX.Possession) in model.closure
    assert (EX.ball, TYPE, EX.Possession) not in delta.removed


def test_retracting_an_inferred_only_triple_changes_nothing() -> None:
    model = Model("m", TBOX)
    model.apply([(EX.tom, TYPE, EX.Cat)], [])
    delta = model.apply([], [(EX.tom, TYPE, EX.Animal)])
    assert not delta
    assert (EX.tom, TYPE, EX.Animal) in model.closure


def test_tbox_change_recompiles_and_rematerialises() -> None:
    model = Model("m", TBOX)
    model.apply([(EX.tom, TYPE, EX.Cat)], [])
    revision = model.tbox_revision
    delta = model.apply([(EX.Animal, RDFS.subClassOf, EX.LivingBeing)], [])
    assert model.tbox_revision == revision + 1
    assert (EX.tom, TYPE, EX.LivingBeing) in model.closure
    assert (EX.tom, TYPE, EX.LivingBeing) in delta.added
    delta = model.apply([], [(EX.Cat, RDFS.subClassOf, EX.Animal)])
    assert model.tbox_revision == revision + 2
    assert (EX.tom, TYPE, EX.Animal) not in model.closure
    assert (EX.tom, TYPE, EX.LivingBeing) not in model.closure
    assert (EX.tom, TYPE, EX.Animal) in delta.removed


def test_new_property_characteristic_recompiles() -> None:
    model = Model("m", [])
    model.apply([(EX.a, EX.near, EX.b)], [])
    assert (EX.b, EX.near, EX.a) not in model.closure
    model.apply([(EX.near, TYPE, OWL.SymmetricProperty)], [])
    assert (EX.b, EX.near, EX.a) in model.closure


def test_models_start_from_the_default_tbox() -> None:
    models = Models(default_ontology())
    assert models.names == [DEFAULT_MODEL]
    assert models.get("bob") is None
    bob = models.create("bob")
    assert models.create("bob") is bob
    assert models.names == [DEFAULT_MODEL, "bob"]
    assert len(bob.asserted) == len(models.default.asserted)  # K15: the same TBox, no facts of default
    bob.apply([(EX.r1, TYPE, EX.Robot)], [])
    assert (EX.r1, TYPE, EX.Agent) in bob.closure
    assert (EX.r1, TYPE, EX.Robot) not in models.default.closure


def test_models_are_independent() -> None:
    models = Models(TBOX)
    models.default.apply([(EX.tom, TYPE, EX.Cat)], [])
    other = models.create("other")
    assert (EX.tom, TYPE, EX.Cat) not in other.closure
    other.apply([(EX.Cat, RDFS.subClassOf, EX.Pet)], [])
    models.default.apply([(EX.tim, TYPE, EX.Cat)], [])
    assert (EX.tim, TYPE, EX.Pet) not in models.default.closure


def test_reset_keeps_or_drops_the_defaults() -> None:
    models = Models(TBOX)
    models.default.apply([(EX.tom, TYPE, EX.Cat)], [])
    models.create("other")
    models.reset(keep_defaults=True)
    assert models.names == [DEFAULT_MODEL]
    assert set(models.default.asserted) == set(TBOX)
    models.default.apply([(EX.tim, TYPE, EX.Cat)], [])
    assert (EX.tim, TYPE, EX.Animal) in models.default.closure
    models.reset(keep_defaults=False)
    assert len(models.default.asserted) == 0
    assert len(models.default.closure) == 0


def test_closure_has_no_top_class_noise() -> None:
    model = Model("m", list(default_ontology()))
    model.apply([(EX.r1, TYPE, EX.Robot)], [])
    classes = model.closure.objects(EX.r1, TYPE)
    assert URIRef("http://www.w3.org/2002/07/owl#Thing") not in classes
    assert URIRef("http://www.w3.org/2000/01/rdf-schema#Resource") not in classes
    assert (EX.r1, URIRef("http://www.w3.org/2002/07/owl#sameAs"), EX.r1) not in model.closure
