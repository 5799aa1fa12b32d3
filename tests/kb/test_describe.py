"""What the KB says about a term (kb-compat §3.3, §3.4): details, label dicts, lookup, about,
label and classesof, including K6, K10, K11, K13 and the tutorial idiom.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest

from kb import KB, KbError
from tests.conftest import VARIANTS, kb_variant

HIDDEN_RELATION_PREDICATES = {
    "rdf:type", "rdfs:subClassOf", "rdfs:label", "rdfs:comment", "rdfs:domain", "rdfs:range",
    "owl:disjointWith", "rdf:first", "openCycUri",
}


# The fixtures run every test against the in-process KB and against a RemoteKB reading a mirror
# of one from a SPARQL store (tests that build a KB themselves stay in-process).


@pytest.fixture(scope="module", params=VARIANTS)
def bare(request: pytest.FixtureRequest) -> Iterator[KB]:
    """A KB without ontology, so that whole details() answers can be compared exactly."""
    with kb_variant(request, ontology=False) as k:
        k += [
            "cup1 rdf:type Cup",
            'Cup rdfs:label "cup"@en',
            "Cup rdfs:subClassOf Tableware",
            "Mug rdfs:subClassOf Cup",
            "myself sees cup1",
            "alfred age 42",
            "cup1 likes alfred",
            "cup1 rdfs:comment \"a comment\"",
            "cup1 rdfs:domain Somewhere",
            "cup1 rdfs:range Elsewhere",
            "cup1 owl:disjointWith Other",
            "cup1 rdf:first item",
            'cup1 openCycUri "http://sw.opencyc.org/concept/Mx4r"',
            "other rdfs:subClassOf cup1",
        ]
        yield k


@pytest.fixture(scope="module", params=VARIANTS)
def world(request: pytest.FixtureRequest) -> Iterator[KB]:
    """The default ontology plus a small tutorial world."""
    with kb_variant(request) as k:
        k += [
            "myself sees cup_abcd",
            "cup_abcd rdf:type dbr:Cup",
            "myself sees book_1",
            "book_1 rdf:type dbr:Book",
            'book_1 rdfs:label "the red book"',
            "person_x rdf:type Human",
            "person_x sees sofa",
            "alfred rdf:type Human",
            "alfred age 42",
            'nono rdfs:label "alfred"',
            'sentence rdfs:label "alfred is a charming person"',
            'j1 rdfs:label "Johnny"@en',
            'j1 rdfs:label "Jean"@fr',
            'j2 rdfs:label "Jojo"',
            'j2 rdfs:label "Jo"@en',
            'j3 rdfs:label "Jacques"@fr',
            "robby rdf:type Robot",
            'robby hasName "Zebulon"',
        ]
        yield k


# --- details: exact shapes -------------------------------------------------------------------


def test_details_of_an_instance_exactly(bare: KB) -> None:
    assert bare.details("myself") == {
        "id": "myself",
        "label": {"default": "myself"},
        "type": "undecided",
        "attributes": [],
        "relations": [["myself", "sees", "cup1"]],
    }
    details = bare.details("cup1")
    assert details["id"] == "cup1"
    assert details["label"] == {"default": "cup1"}
    assert details["type"] == "instance"
    assert details["attributes"] == [
        {
            "name": "Classes",
            "id": "classes",
            "values": [{"id": "Cup", "label": {"en": "cup", "default": "cup"}}],
        },
    ]


def test_details_relations_filtering(bare: KB) -> None:
    # Only sees/likes survive: every hidden predicate is dropped when cup1 is subject or object.
    assert bare.details("cup1")["relations"] == [["cup1", "likes", "alfred"], ["myself", "sees", "cup1"]]


@pytest.mark.parametrize(
    "predicate", ["rdfs:comment", "rdfs:domain", "owl:disjointWith", "rdf:first", "likes"]
)
def test_details_of_a_predicate_keeps_all_its_triples(bare: KB, predicate: str) -> None:
    relations = bare.details(predicate)["relations"]
    assert relations
    assert all(r[1] == predicate for r in relations)
    assert any(r[0] == "cup1" for r in relations)


def test_details_of_a_class_exactly(bare: KB) -> None:
    details = bare.details("Cup")
    assert details["id"] == "Cup"
    assert details["label"] == {"en": "cup", "default": "cup"}
    assert details["type"] == "class"
    parents, children, instances = details["attributes"]
    assert [a["id"] for a in details["attributes"]] == ["superClasses", "subClasses", "instances"]
    assert [a["name"] for a in details["attributes"]] == ["Parents", "Children", "Instances"]
    # K10: every attribute value carries "label"; Parents may also carry upstream's "name".
    assert [{"id": v["id"], "label": v["label"]} for v in parents["values"]] == [
        {"id": "Tableware", "label": {"default": "Tableware"}}
    ]
    assert all(v.get("name", v["label"]) == v["label"] for v in parents["values"])
    assert children["values"] == [{"id": "Mug", "label": {"default": "Mug"}}]
    assert instances["values"] == [{"id": "cup1", "label": {"default": "cup1"}}]


def test_class_attributes_are_direct_only(bare: KB) -> None:
    tableware = bare.details("Tableware")["attributes"]
    assert [v["id"] for v in tableware[1]["values"]] == ["Cup"]  # not Mug
    assert tableware[2]["values"] == []  # cup1 is a Tableware only by inference


@pytest.mark.parametrize(
    ("term", "kind"),
    [
        ("age", "datatype_property"),  # used as a predicate with a literal object
        ("sees", "object_property"),  # used as a predicate with a resource object
        ("Tableware", "class"),  # has subclasses
        ("nobody_knows_me", "undecided"),
    ],
)
def test_term_kind_without_ontology(bare: KB, term: str, kind: str) -> None:
    details = bare.details(term)
    assert details["type"] == kind
    if kind != "class":
        assert details["attributes"] == []


def test_details_of_an_unknown_term_exactly(bare: KB) -> None:
    assert bare.details("nobody_knows_me") == {
        "id": "nobody_knows_me",
        "label": {"default": "nobody_knows_me"},
        "type": "undecided",
        "attributes": [],
        "relations": [],
    }


@pytest.mark.parametrize(
    ("term", "kind"),
    [
        ("sees", "object_property"),
        ("hasColor", "object_property"),
        ("isPerceived", "datatype_property"),
        ("hasName", "datatype_property"),
        ("Human", "class"),
        ("dbr:Cup", "class"),
        ("dbr:Table_(furniture)", "class"),
        ("cyc:SpatialThing-Localized", "class"),
        ("myself", "instance"),
        ("cup_abcd", "instance"),
        ("red", "instance"),
        ("age", "datatype_property"),
        ('"alfred"', "literal"),
        ("42", "literal"),
    ],
)
def test_term_kind_with_ontology(world: KB, term: str, kind: str) -> None:
    assert world.details(term)["type"] == kind


def test_details_keys(world: KB) -> None:
    for term in ("cup_abcd", "Human", "sees", "nobody", '"alfred"'):
        assert set(world.details(term)) == {"id", "label", "type", "attributes", "relations"}


def test_details_relations_include_inferred_triples(world: KB) -> None:
    relations = world.details("person_x")["relations"]
    assert ["person_x", "sees", "sofa"] in relations
    assert not [r for r in relations if r[1] in HIDDEN_RELATION_PREDICATES]
    # sofa is typed only by inference from the range of sees, and is no class.
    assert world.details("sofa")["type"] == "instance"


def test_instance_classes_are_direct_and_hide_noise(world: KB) -> None:
    world_classes = world.details("myself")["attributes"][0]
    assert world_classes["id"] == "classes"
    ids = [v["id"] for v in world_classes["values"]]
    assert ids == ["foaf:Agent"]  # asserted: foaf:Agent and owl:NamedIndividual (hidden)


def test_active_concept_is_not_listed_as_a_class() -> None:
    with KB(clock=lambda: 0.0) as k:
        k += ["cup_9 rdf:type dbr:Cup", "cup_9 rdf:type ActiveConcept"]
        values = k.details("cup_9")["attributes"][0]["values"]
        assert [v["id"] for v in values] == ["dbr:Cup"]
        assert k.classesof("cup_9", direct=True) == ["dbr:Cup"]


def test_tutorial_idiom(world: KB) -> None:
    objects = [r["obj"] for r in world["myself sees ?obj"]]
    assert objects == ["book_1", "cup_abcd"]
    assert [world.details(o)["label"]["default"] for o in objects] == ["the red book", "cup_abcd"]
    class_names = [world.details(o)["attributes"][0]["values"][0]["label"]["default"] for o in objects]
    assert class_names == ["book", "cup"]


# --- label dict ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("term", "labels"),
    [
        ("j1", {"en": "Johnny", "fr": "Jean", "default": "Johnny"}),
        ("j2", {"default": "Jojo", "en": "Jo"}),
        ("j3", {"fr": "Jacques", "default": "j3"}),
        ("book_1", {"default": "the red book"}),
        ("cup_abcd", {"default": "cup_abcd"}),
        ("dbr:Cup", {"en": "cup", "fr": "tasse", "default": "cup"}),
        ("dbr:NoSuchThing", {"default": "dbr:NoSuchThing"}),
        ("<http://example.org/x#y>", {"default": "http://example.org/x#y"}),
    ],
)
def test_label_dict(world: KB, term: str, labels: dict[str, str]) -> None:
    assert world.details(term)["label"] == labels


@pytest.mark.parametrize(
    ("term", "lang", "text"),
    [
        ("j1", None, "Johnny"),
        ("j1", "fr", "Jean"),
        ("j1", "en", "Johnny"),
        ("j1", "de", "Johnny"),
        ("j2", None, "Jojo"),
        ("j2", "en", "Jo"),
        ("j3", None, "j3"),
        ("j3", "fr", "Jacques"),
        ("Human", "fr", "humain"),
        ("dbr:Cup", None, "cup"),
        ("dbr:Cup", "fr", "tasse"),
        ("nobody", None, "nobody"),
    ],
)
def test_label_returns_a_string_with_fallback(world: KB, term: str, lang: str | None, text: str) -> None:
    assert world.label(term, lang) == text  # K6


# --- K11: no noise in details, classesof, lookup ---------------------------------------------


def _walk(value: Any) -> Iterator[Any]:
    if isinstance(value, dict):
        for v in value.values():
            yield from _walk(v)
    elif isinstance(value, list):
        for v in value:
            yield from _walk(v)
    else:
        yield value


@pytest.mark.parametrize(
    "term",
    ["EmbodiedAgent", "foaf:Agent", "cyc:Hand", "PhysicalSupport", "Obstacle", "dbr:Book", "myself", "robby"],
)
def test_no_blank_nodes_or_top_classes_in_details(world: KB, term: str) -> None:
    for value in _walk(world.details(term)):
        if isinstance(value, str):
            assert not value.startswith("_:"), value
            assert value not in ("owl:Thing", "rdfs:Resource", "None"), value
            assert "genid" not in value and "bnode" not in value.lower(), value


@pytest.mark.parametrize("term", ["robby", "myself", "cup_abcd", "person_x", "sofa"])
def test_classesof_hides_noise(world: KB, term: str) -> None:
    for direct in (True, False):
        classes = world.classesof(term, direct)
        assert classes or (direct and term == "sofa")  # sofa is typed only by inference
        assert all(isinstance(c, str) and c for c in classes)
        assert not {"owl:Thing", "rdfs:Resource", "owl:NamedIndividual", "ActiveConcept"} & set(classes)
        assert not [c for c in classes if c.startswith("_:") or c == "None"]


def test_no_self_same_as_in_details_or_about() -> None:
    with KB() as k:
        k += ["ghost owl:sameAs ghost", "ghost sees cup"]
        assert ["ghost", "owl:sameAs", "ghost"] not in k.details("ghost")["relations"]
        assert ["ghost", "owl:sameAs", "ghost"] not in k.about("ghost")


def test_blank_nodes_never_leak_through_lookup_about_or_find() -> None:
    with KB() as k:
        k.load_data(
            "@prefix : <http://kb.openrobots.org#> .\n"
            "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .\n"
            '[] :sees :ghostcup ; rdfs:label "ghost" . :ghostcup :isIn [ rdfs:label "ghostroom" ] .'
        )
        assert k.lookup("ghost") == [["ghostcup", "instance"]]
        assert k.lookup("ghostroom") == []
        for statement in k.about("ghostcup") + k.about("ghost"):
            assert None not in statement and "None" not in statement
            assert not any(isinstance(v, str) and v.startswith("_:") for v in statement)
        assert k["?x sees ghostcup"] == []
        assert k["ghostcup isIn ?r"] == []
        assert [r for r in k.details("ghostcup")["relations"] if None in r or "None" in r] == []


def test_owl_thing_is_not_looked_up() -> None:
    with KB() as k:
        k += ["thingy rdf:type owl:Thing"]
        assert ["owl:Thing", "class"] not in k.lookup("owl:Thing")
        assert [name for name, _ in k.lookup("Thing") if name == "owl:Thing"] == []
        assert "owl:Thing" not in k.classesof("thingy")
        assert "owl:Thing" not in k.classesof("thingy", direct=True)


# --- lookup (§3.4) ---------------------------------------------------------------------------


def test_lookup_reference_expectation(world: KB) -> None:
    assert world.lookup("alfred") == [
        ["alfred", "instance"], ["nono", "undecided"], ["sentence", "undecided"]
    ]


def test_lookup_age_puts_the_exact_datatype_property_first(world: KB) -> None:
    found = world.lookup("age")
    assert found[0] == ["age", "datatype_property"]
    assert ["age", "datatype_property"] not in found[1:]
    assert len(found) > 1  # approximate matches follow (e.g. EngagementLevel)


def test_lookup_exact_before_approximate_and_case_insensitive(world: KB) -> None:
    found = world.lookup("ALFRED")
    assert sorted(found) == [["alfred", "instance"], ["nono", "undecided"], ["sentence", "undecided"]]
    found = world.lookup("charming")
    assert found == [["sentence", "undecided"]]


def test_lookup_searches_labels_in_every_language(world: KB) -> None:
    assert world.lookup("Jean") == [["j1", "undecided"]]
    assert world.lookup("humain") == [["Human", "class"]]


def test_lookup_by_label_yields_the_labelled_term(world: KB) -> None:
    assert world.lookup("cup")[0] == ["dbr:Cup", "class"]  # exact label match, before cup_abcd
    assert ["cup_abcd", "instance"] in world.lookup("cup")[1:]


def test_lookup_of_a_non_label_literal_yields_the_literal(world: KB) -> None:
    assert world.lookup("Zebulon") == [["Zebulon", "literal"]]


def test_lookup_of_a_literal_object(world: KB) -> None:
    assert world.lookup("42") == [[42, "literal"]] or world.lookup("42") == [["42", "literal"]]


def test_lookup_shape(world: KB) -> None:
    for entry in world.lookup("cup"):
        assert isinstance(entry, list) and len(entry) == 2
        assert entry[1] in {
            "instance", "class", "object_property", "datatype_property", "undecided", "literal"
        }


def _gizmo_kb(statements: list[str]) -> list[list[Any]]:
    with KB(ontology=False) as k:
        for s in statements:
            k += s
        return k.lookup("gizmo")


def test_lookup_order_is_deterministic() -> None:
    statements = [
        'thing2 rdfs:label "gizmo"',
        'thing1 rdfs:label "gizmo"',
        "gizmo rdf:type Tool",
        'zed rdfs:label "big gizmo"',
        'abc rdfs:label "Gizmos"',
        "gizmo_2 likes x",
    ]
    first = _gizmo_kb(statements)
    assert first == _gizmo_kb(list(reversed(statements)))  # K13
    assert first[:3] == [["gizmo", "instance"], ["thing1", "undecided"], ["thing2", "undecided"]]
    assert sorted(first[3:]) == [["abc", "undecided"], ["gizmo_2", "undecided"], ["zed", "undecided"]]


def test_lookup_honours_models() -> None:
    with KB(ontology=False) as k:
        k.add(["secret_thing likes x"], models=["other"])
        assert k.lookup("secret_thing") == []
        assert k.lookup("secret_thing", models=["other"]) == [["secret_thing", "undecided"]]
        assert k.lookup("secret_thing", models=["all"]) == [["secret_thing", "undecided"]]
        with pytest.raises(KbError, match="nope"):
            k.lookup("secret_thing", models=["nope"])


# --- about (§3.4) ----------------------------------------------------------------------------


def test_about_covers_subject_predicate_object_and_inferred(world: KB) -> None:
    about = world.about("cup_abcd")
    assert ["myself", "sees", "cup_abcd"] in about
    assert ["cup_abcd", "rdf:type", "dbr:Cup"] in about
    assert ["cup_abcd", "rdf:type", "Tableware"] in about  # inferred
    assert all(isinstance(st, list) and len(st) == 3 for st in about)
    assert len({tuple(st) for st in about}) == len(about)
    assert ["alfred", "age", 42] in world.about("age")


def test_about_includes_labels_containing_the_raw_text_case_sensitively(world: KB) -> None:
    assert world.about("charming") == [["sentence", "rdfs:label", "alfred is a charming person"]]
    assert world.about("Charming") == []
    assert world.about("a charming person") == [["sentence", "rdfs:label", "alfred is a charming person"]]


# --- classesof (§3.4) ------------------------------------------------------------------------


def test_classesof_direct_and_inferred(world: KB) -> None:
    assert world.classesof("cup_abcd", direct=True) == ["dbr:Cup"]
    inferred = world.classesof("cup_abcd")
    assert {"dbr:Cup", "Tableware", "Artifact", "cyc:PartiallyTangible"} <= set(inferred)
    assert inferred == sorted(inferred)
    assert world.classesof("alfred", True) == ["Human"]
    assert {"Human", "foaf:Person", "EmbodiedAgent", "foaf:Agent", "Agent"} <= set(world.classesof("alfred"))
    assert world.classesof("nobody") == []


@pytest.mark.parametrize("direct", [False, True])
def test_all_classes_are_classesof_of_every_typed_term(world: KB, direct: bool) -> None:
    every = world.all_classes(direct)
    assert every["cup_abcd"] == world.classesof("cup_abcd", direct)
    assert every["alfred"] == world.classesof("alfred", direct)
    assert "nobody" not in every and "sentence" not in every  # untyped: no entry
    for term, classes in every.items():
        assert classes == world.classesof(term, direct), term


@pytest.mark.parametrize("lang", [None, "en", "fr"])
def test_all_labels_are_the_label_of_every_labelled_term(world: KB, lang: str | None) -> None:
    every = world.all_labels(lang)
    assert every["book_1"] == "the red book" and "cup_abcd" not in every  # unlabelled: no entry
    assert every["j1"] == world.label("j1", lang) and every["j3"] == world.label("j3", lang)
    for term, text in every.items():
        assert text == world.label(term, lang), term


def test_bulk_reads_check_their_arguments(world: KB) -> None:
    with pytest.raises(KbError, match="lang"):
        world.all_labels(lang=3)  # type: ignore[arg-type]
    with pytest.raises(KbError, match="nope"):
        world.all_classes(model="nope")


def test_term_errors_are_kb_errors(world: KB) -> None:
    for call in (world.details, world.label, world.classesof):
        with pytest.raises(KbError):
            call("")
    with pytest.raises(KbError, match="nope"):
        world.details("cup_abcd", models=["nope"])


def test_details_origin_flags_asserted_and_inferred_relations() -> None:
    from kb import KB

    with KB() as kb:
        kb += ["cup_1 isOn table_1", "cup_1 rdf:type dbr:Cup"]
        plain = kb.details("cup_1")
        flagged = kb.details("cup_1", origin=True)
        assert flagged["relations"] == plain["relations"] and "asserted" not in plain
        origin = dict(zip(map(tuple, flagged["relations"]), flagged["asserted"], strict=True))
        assert origin[("cup_1", "isOn", "table_1")] is True
        assert origin[("cup_1", "isAt", "table_1")] is False
        assert origin[("cup_1", "isMovable", True)] is False
