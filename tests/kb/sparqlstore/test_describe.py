"""What the replica's describe queries (kb.sparqlstore.describe) rely on: lookup scans only the
asserted graph for names and literals, because the reasoner writes no term it was not given
(besides REASONER_TERMS). The answers themselves are compared with KB's in test_remote.py and by
the fixture tables of test_describe.py."""

from __future__ import annotations

import pytest

from kb import KB
from kb.sparqlstore.describe import REASONER_TERMS

RULES = """@prefix : <http://kb.openrobots.org#> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
:Car rdfs:subClassOf :Vehicle . :Auto owl:equivalentClass :Car .
:drives rdfs:domain :Driver ; rdfs:range :Vehicle .
:owns rdfs:subPropertyOf :has . :has owl:equivalentProperty :possesses . :ownedBy owl:inverseOf :owns .
:near a owl:SymmetricProperty . :above a owl:TransitiveProperty .
:RedThing owl:equivalentClass [ a owl:Restriction ; owl:onProperty :color ; owl:hasValue :red ] .
:RedCar owl:equivalentClass [ owl:intersectionOf ( :Car :RedThing ) ] .
:c1 a :Auto ; :color :red . :bob :drives :c1 ; :owns :c1 . :a :near :b . :x :above :y . :y :above :z .
:r1 a :RedThing . :n1 :label_of "a name" .
"""


@pytest.mark.parametrize("ontology", [True, False], ids=["oro", "rules"])
def test_the_reasoner_writes_no_term_it_was_not_given(ontology: bool) -> None:
    """kb.sparqlstore.describe.lookup_text scans only the asserted graph for names and literals."""
    with KB(ontology=ontology) as kb:
        kb.load_data(RULES)
        kb += ["myself sees cup_1", "cup_1 rdf:type dbr:Cup", "cup_1 isOn table_1", "p1 rdf:type foaf:Person",
               "a1 leftOf a2", "a2 leftOf a3", "cup_1 isNextTo plate_1", "robby hasName \"Zebulon\""]
        model = kb.writer.models.default
        for derived_fact in ["c1 rdf:type Vehicle", "c1 rdf:type RedCar", "bob rdf:type Driver", "bob has c1",
                             "bob possesses c1", "c1 ownedBy bob", "b near a", "x above z", "r1 color red"]:
            assert kb.exist(derived_fact), derived_fact  # every rule ran
        given = {t for triple in model.asserted for t in triple}
        derived = {t for triple in model.closure for t in triple}
        assert derived - given <= REASONER_TERMS
