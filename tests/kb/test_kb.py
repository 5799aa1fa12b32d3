"""The knowledge_core facade (kb-compat §2, §3): conformance tables for every call and its exact
return shape, the K-requirements visible through the API, and reasoning seen by clients.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from typing import Any

import pytest

from kb import KB, KbError, __version__
from tests.conftest import VARIANTS, kb_variant

# The conformance fixtures run every test against the in-process KB and against a RemoteKB
# reading a mirror of one from a SPARQL store (tests that build a KB with special arguments
# stay in-process).


@pytest.fixture(params=VARIANTS)
def kb(request: pytest.FixtureRequest) -> Iterator[KB]:
    with kb_variant(request) as k:
        yield k


TUTORIAL = [
    "myself sees cup_abcd",
    "myself sees sofa",
    "person_x sees sofa",
    "cup_abcd rdf:type dbr:Cup",
    "person_x rdf:type Human",
    "person_x sees cup_abcd",
    "person_x looksAt cup_abcd",
    "person_x looksAt sofa",
    "myself looksAt sofa",
]


@pytest.fixture(scope="module", params=VARIANTS)
def shared(request: pytest.FixtureRequest) -> Iterator[KB]:
    """One KB for tests that only touch their own subjects (or write nothing), to keep the suite fast."""
    with kb_variant(request) as k:
        yield k


@pytest.fixture(scope="module", params=VARIANTS)
def world(request: pytest.FixtureRequest) -> Iterator[KB]:
    with kb_variant(request) as k:
        k += TUTORIAL
        yield k


# --- §3.1 summary: every call and the type it returns -----------------------------------------


def test_summary_table(world: KB) -> None:
    assert isinstance(world["myself sees ?o"], list)
    assert all(isinstance(r, dict) for r in world["myself sees ?o"])
    assert isinstance(world.find(["myself sees ?o"]), list)
    assert world.exist(["myself sees cup_abcd"]) is True
    assert world.exist(["myself sees nothing"]) is False
    assert all(isinstance(st, list) and len(st) == 3 for st in world.about("cup_abcd"))
    assert all(isinstance(e, list) and len(e) == 2 for e in world.lookup("cup"))
    assert isinstance(world.details("cup_abcd"), dict)
    assert isinstance(world.label("cup_abcd"), str)
    assert all(isinstance(c, str) for c in world.classesof("cup_abcd"))
    assert isinstance(world.hello(), str)
    assert isinstance(world.stats(), dict)
    assert all(isinstance(m, str) for m in world.methods())


# --- §3.2 queries ----------------------------------------------------------------------------


def test_reference_examples(world: KB) -> None:
    assert world["myself sees ?obj"] == [{"obj": "cup_abcd"}, {"obj": "sofa"}]
    assert world["* sees *"] == [
        {"var1": "myself", "var2": "cup_abcd"},
        {"var1": "myself", "var2": "sofa"},
        {"var1": "person_x", "var2": "cup_abcd"},
        {"var1": "person_x", "var2": "sofa"},
    ]
    grounding = ["?h sees ?o", "?o rdf:type dbr:Cup", "?h rdf:type Human"]
    assert world[grounding] == [{"h": "person_x", "o": "cup_abcd"}]


def test_variables_named_with_two_underscores_are_anonymous_as_in_knowledge_core(world: KB) -> None:
    # knowledge_core's clients write each '*' as '?__<random>': the rows read the same either way.
    assert world.find(["?__xyz sees ?__abc"]) == world["* sees *"]
    assert world.find(["?__a sees ?__b"], ["?__a", "?__b"])[0] == {"var1": "myself", "var2": "cup_abcd"}
    assert world.find(["?agent looksAt ?__what"], ["?agent", "?__what"]) == world["?agent looksAt *"]


def test_rows_are_distinct_after_projection(world: KB) -> None:
    assert world["?agent looksAt *"] == [{"agent": "myself"}, {"agent": "person_x"}]  # K1
    assert world.find(["?a sees ?o"], vars=["?a"]) == [{"a": "myself"}, {"a": "person_x"}]


@pytest.mark.parametrize(
    ("vars", "expected"),
    [
        (["?h"], [{"h": "person_x"}]),
        (["h"], [{"h": "person_x"}]),
        (["?o", "?h"], [{"o": "cup_abcd", "h": "person_x"}]),
        (None, [{"h": "person_x", "o": "cup_abcd"}]),
    ],
)
def test_find_vars(world: KB, vars: list[str] | None, expected: list[dict[str, str]]) -> None:
    assert world.find(["?h sees ?o", "?o rdf:type dbr:Cup", "?h rdf:type Human"], vars) == expected


def test_find_positional_argument_order(world: KB) -> None:
    # find(patterns, vars, models) (K18)
    assert world.find(["?h sees ?o"], ["?o"], ["default"]) == [{"o": "cup_abcd"}, {"o": "sofa"}]


@pytest.mark.parametrize(
    ("patterns", "expected"),
    [
        ("person_x rdf:type Human", ["person_x rdf:type Human"]),
        (["person_x rdf:type Human", "myself sees sofa"], ["person_x rdf:type Human", "myself sees sofa"]),
        ("person_x rdf:type Agent", ["person_x rdf:type Agent"]),  # inferred
        ("person_x rdf:type Robot", []),
        (["person_x rdf:type Human", "myself sees person_x"], []),
    ],
)
def test_ground_patterns_return_the_patterns_or_nothing(
    world: KB, patterns: Any, expected: list[str]
) -> None:
    assert world[patterns] == expected
    assert world.find(patterns) == expected


@pytest.mark.parametrize(
    ("patterns", "expected"),
    [
        (["myself sees cup_abcd"], True),
        (["myself sees ?x"], True),
        (["myself sees ?x", "?x rdf:type dbr:Cup"], True),
        (["myself sees ?x", "?x rdf:type Human"], False),
        (["myself sees nothing"], False),
        ("* looksAt sofa", True),
    ],
)
def test_exist(world: KB, patterns: Any, expected: bool) -> None:
    assert world.exist(patterns) is expected


def test_exist_honours_models(kb: KB) -> None:
    kb.add("r2 sees cup", models=["bob"])
    assert kb.exist(["r2 sees cup"]) is False
    assert kb.exist(["r2 sees cup"], ["bob"]) is True  # K7, positional
    assert kb.exist(["r2 sees ?x"], models=["bob"]) is True
    assert kb.exist(["r2 sees ?x"], models=["all"]) is True
    with pytest.raises(KbError, match="nope"):
        kb.exist(["r2 sees ?x"], models=["nope"])


def test_getitem_forms(world: KB) -> None:
    rows = [{"h": "myself", "o": "cup_abcd"}, {"h": "person_x", "o": "cup_abcd"}]
    assert world["?h sees ?o", "?o rdf:type dbr:Cup"] == rows
    assert world[("?h sees ?o", "?o rdf:type dbr:Cup")] == rows
    assert world["?h sees ?o", "?o rdf:type dbr:Cup", ["default"]] == rows
    assert world[["?h sees ?o", "?o rdf:type dbr:Cup"], ["default"]] == rows
    assert world["?h sees ?o", "?o rdf:type dbr:Cup", ["all"]] == rows
    assert world["myself sees ?obj", ["default"]] == [{"obj": "cup_abcd"}, {"obj": "sofa"}]
    with pytest.raises(KbError, match="nope"):
        world["myself sees ?obj", ["nope"]]


@pytest.mark.parametrize("text", ["cup_abcd", "cup", "some words here", "a b c d", 'open "quote'])
def test_getitem_with_other_than_three_tokens_is_lookup(world: KB, text: str) -> None:
    assert world[text] == world.lookup(text)


def test_getitem_lookup_of_a_label_with_spaces() -> None:
    with KB() as k:
        k += ['sentence rdfs:label "alfred is a charming person"', 'nono rdfs:label "alfred"']
        assert k["alfred is a charming person"] == [["sentence", "undecided"]]
        assert k["alfred"] == [["nono", "undecided"], ["sentence", "undecided"]]


def test_contains(world: KB) -> None:
    assert "cup_abcd" in world
    assert "sofa" in world
    assert "never_heard_of_it" not in world
    assert "myself sees *" in world
    assert "myself sees cup_abcd" in world
    assert "myself sees person_x" not in world
    assert "* looksAt ?what" in world


# --- K2: literal patterns through every entry point -------------------------------------------


LITERALS = [
    '"alfred"',
    '"alfred is a charming person"',
    '"hello, world."',
    '"bonjour"@fr',
    '"it\'s \\"quoted\\""',
    '"""two\nlines"""',
    "42",
    "4.5",
    "-3",
    "true",
    '"10"^^xsd:integer',
]


@pytest.mark.parametrize("literal", LITERALS)
def test_literal_patterns_everywhere(shared: KB, literal: str) -> None:
    kb = shared
    kb += f"thing_1 note_a {literal}"
    assert kb[f"?x note_a {literal}"] == [{"x": "thing_1"}]
    assert kb.find([f"?x note_a {literal}"]) == [{"x": "thing_1"}]
    assert kb[f"thing_1 note_a {literal}"] == [f"thing_1 note_a {literal}"]
    assert f"thing_1 note_a {literal}" in kb
    assert f"* note_a {literal}" in kb
    assert kb.exist([f"?x note_a {literal}"])
    kb -= f"thing_1 note_a {literal}"
    assert kb["thing_1 note_a ?v"] == []
    kb += f"thing_1 note_a {literal}"
    kb -= f"?x note_a {literal}"
    assert kb["thing_1 note_a ?v"] == []


@pytest.mark.parametrize(
    ("literal", "value"),
    [
        ('"alfred"', "alfred"),
        ('"hello, world."', "hello, world."),
        ('"bonjour"@fr', "bonjour"),
        ('"""two\nlines"""', "two\nlines"),
        ("42", 42),
        ("-5", -5),
        ("4.5", 4.5),
        ("0.0", 0.0),
        ("1.3e2", 130.0),
        ("true", True),
        ("false", False),
        ('"10"^^xsd:integer', 10),
    ],
)
def test_literals_come_back_as_native_values(shared: KB, literal: str, value: Any) -> None:
    subject = f"thing_2_{abs(hash(literal))}"
    shared += f"{subject} note_b {literal}"
    found = shared[f"{subject} note_b ?v"]
    shared -= f"{subject} note_b ?v"
    assert found == [{"v": value}]
    assert type(found[0]["v"]) is type(value)


# --- K3, K4, K17: names come back as written and can be reused --------------------------------


@pytest.mark.parametrize(
    "name",
    [
        "living-room",
        "dbr:Table_(furniture)",
        "dbr:Shelf_(storage)",
        "cyc:Table-PieceOfFurniture",
        "cyc:SpatialThing-Localized",
        "sim_person_abcde",
        "anonymous_person_abcde",
        "cup_zmfla",
        "foaf:Agent",
        "v1.2",
        "http://example.org/foo#bar",
        "pièce_1",
        "dbr:São_Paulo",
    ],
)
def test_names_round_trip(shared: KB, name: str) -> None:
    kb = shared
    written = f"<{name}>" if name.startswith("http") else name
    kb += f"thing_3 isIn {written}"
    assert kb["thing_3 isIn ?where"] == [{"where": name}]
    assert kb[f"?x isIn {name}"] == [{"x": "thing_3"}]
    assert kb[f"{name} placeOf ?x"] == [{"x": "thing_3"}]
    kb -= f"thing_3 isIn {name}"
    assert kb["thing_3 isIn ?where"] == []


def test_unknown_namespaces_are_returned_in_full(kb: KB) -> None:
    kb += "<http://example.org/a#x> likes <https://other.example/y>"
    assert kb["?s likes ?o"] == [{"s": "http://example.org/a#x", "o": "https://other.example/y"}]  # K17
    assert not [r for r in kb["?s likes ?o"] if re.match(r"ns\d+:", r["s"])]


# --- §1 errors through the facade --------------------------------------------------------------


@pytest.mark.parametrize(
    ("call", "stmt", "what"),
    [
        ("add", "x sees", "expected 3 terms"),
        ("add", "x sees y z", "expected 3 terms"),
        ("add", "x foo:sees y", "unknown prefix"),
        ("add", '"lit" sees y', "subject"),
        ("add", 'x "lit" y', "predicate"),
        ("add", "x sees ?y", "not allowed"),
        ("add", "x sees *", "not allowed"),
        ("add", 'x sees "abc', "unterminated"),
        ("add", 'x sees ab"c', "quote"),
        ("find", "x sees", "expected 3 terms"),
        ("find", "?x foo:sees y", "unknown prefix"),
        ("find", '?x sees "abc', "unterminated"),
        ("remove", "x sees", "expected 3 terms"),
        ("remove", "?x zz:p ?y", "unknown prefix"),
        ("exist", "x sees", "expected 3 terms"),
    ],
)
def test_errors_name_the_statement(shared: KB, call: str, stmt: str, what: str) -> None:
    kb = shared
    with pytest.raises(KbError) as err:
        getattr(kb, call)([stmt])
    assert what in str(err.value)
    assert stmt in str(err.value) or repr(stmt) in str(err.value)


@pytest.mark.parametrize("models", [["bad name"], [""], [123], ["a/b"]])
def test_bad_model_names(shared: KB, models: Any) -> None:
    kb = shared
    with pytest.raises(KbError, match="model"):
        kb.add("x sees y", models=models)
    with pytest.raises(KbError, match="model"):
        kb.find("?x sees y", models=models)


@pytest.mark.parametrize("bad", [None, 42, ["x sees y", None], b"x sees y"])
def test_non_string_statements(shared: KB, bad: Any) -> None:
    kb = shared
    with pytest.raises(KbError):
        kb.add(bad)
    assert kb["x sees ?y"] == []


@pytest.mark.parametrize(
    "call",
    [
        pytest.param(lambda k: k.label("alfred", 5), id="label-lang-int"),
        pytest.param(lambda k: k.find("?x sees ?y", vars=[5]), id="find-vars-int"),
        pytest.param(lambda k: k.find("?x sees ?y", vars=["?"]), id="find-vars-empty-name"),
        pytest.param(lambda k: k.details(None), id="details-none"),
        pytest.param(lambda k: k.lookup(None), id="lookup-none"),
        pytest.param(lambda k: k.load(None), id="load-none"),
        pytest.param(lambda k: k.load_data("", "nonsensefmt"), id="load-data-unknown-format"),
        pytest.param(lambda k: k.load_data(None), id="load-data-none"),
        pytest.param(lambda k: k.sparql(None), id="sparql-none"),
        pytest.param(lambda k: k.revise("alfred sees cup", None), id="revise-no-policy"),
    ],
)
def test_bad_arguments_are_kb_errors(shared: KB, call: Any) -> None:
    kb = shared
    kb += "alfred sees cup"
    before = kb.size()
    with pytest.raises(KbError):
        call(kb)
    assert kb.size() == before


@pytest.mark.parametrize("callback", [None, "not callable", 42])
def test_subscribe_needs_a_callable(kb: KB, callback: Any) -> None:
    with pytest.raises(KbError):
        kb.subscribe("?x sees ?y", callback)
    kb += "alfred sees cup"  # no half-registered subscription breaks later writes


def test_vars_as_a_single_string(shared: KB) -> None:
    kb = shared
    kb += "alfred sees cup"
    try:
        found = kb.find("?x sees ?y", vars="?x")
    except KbError:
        return  # refusing it clearly is fine
    assert found == [{"x": "alfred"}]


def test_empty_queries_are_refused(kb: KB) -> None:
    with pytest.raises(KbError):
        kb.find([])
    with pytest.raises(KbError):
        kb.exist([])


# --- §2 models -------------------------------------------------------------------------------


def test_default_model(kb: KB) -> None:
    assert kb.models() == ["default"]
    kb.add("alfred sees cup", models=None)
    assert kb.find("alfred sees ?x", models=[]) == [{"x": "cup"}]
    assert kb.find("alfred sees ?x", models=["default"]) == [{"x": "cup"}]


def test_named_models_are_created_on_write_with_the_tbox(kb: KB) -> None:
    kb.add(["r2 rdf:type Robot", "r2 sees cup"], models=["bob"])
    assert kb.models() == ["default", "bob"]
    assert kb.find("?x rdf:type Agent", models=["bob"]) == [{"x": "myself"}, {"x": "r2"}]  # K15
    assert kb.find("?x rdf:type Agent") == [{"x": "myself"}]
    assert kb.find("cup placeOf ?x", models=["bob"]) == []
    kb.add("cup2 isIn kitchen", models="bob")
    assert kb.find("kitchen placeOf ?x", models=["bob"]) == [{"x": "cup2"}]


def test_all_models_union_is_distinct(kb: KB) -> None:
    kb += ["alfred sees cup", "alfred rdf:type Human"]
    kb.add(["alfred sees cup", "r2 sees cup"], models=["bob"])
    assert kb.find("?x sees cup", models=["all"]) == [{"x": "alfred"}, {"x": "r2"}]  # K1
    assert kb.find("?x sees cup", models=["default", "bob"]) == [{"x": "alfred"}, {"x": "r2"}]
    assert kb["?x sees cup", ["all"]] == [{"x": "alfred"}, {"x": "r2"}]


def test_unknown_model_on_read(kb: KB) -> None:
    for call in (
        lambda: kb.find("?x sees ?y", models=["ghost"]),
        lambda: kb.about("cup", models=["ghost"]),
        lambda: kb.lookup("cup", models=["ghost"]),
        lambda: kb.details("cup", models=["ghost"]),
        lambda: kb.classesof("cup", models=["ghost"]),
        lambda: kb.sparql("ASK { ?s ?p ?o }", "ghost"),
    ):
        with pytest.raises(KbError, match="ghost"):
            call()
    assert kb.models() == ["default"]


def test_details_and_sparql_take_one_model(kb: KB) -> None:
    kb.add("r2 rdf:type Robot", models=["bob"])
    assert kb.details("r2", models=["bob"])["type"] == "instance"
    assert kb.details("r2")["type"] == "undecided"
    with pytest.raises(KbError, match="one model"):
        kb.details("r2", models=["default", "bob"])
    with pytest.raises(KbError, match="one model"):
        kb.details("r2", models=["all"])


def test_writing_to_all_writes_every_existing_model(kb: KB) -> None:
    kb.add("x sees y", models=["bob"])
    kb.add("alfred sees cup", models=["all"])
    assert kb.models() == ["default", "bob"]
    assert kb.find("alfred sees ?x", models=["bob"]) == [{"x": "cup"}]
    assert kb.find("alfred sees ?x") == [{"x": "cup"}]


def test_apply_models_gives_each_model_its_own_changes_in_one_revision(kb: KB) -> None:
    kb += ["cup isOn table", "cup belongsTo alice"]
    kb.add("cup isOn shelf", models=["bob"])
    revision = kb.revision
    kb.apply_models({"bob": {"add": ["cup belongsTo bob", "cup isOn sofa"], "remove": ["cup isOn shelf"]},
                     "default": {"add": ["cup hasColor red"], "remove": ["cup belongsTo alice"]},
                     "carol": {"add": "cup isOn table"}})  # a new model, and one statement as a string
    assert kb.revision == revision + 1
    def facts(model: str) -> list[tuple[str, str]]:
        return sorted((p, str(r["o"])) for p in ("belongsTo", "isOn", "hasColor")
                      for r in kb.find(f"cup {p} ?o", models=[model]))

    assert facts("bob") == [("belongsTo", "bob"), ("isOn", "sofa")]
    assert facts("default") == [("hasColor", "red"), ("isOn", "table")]
    assert facts("carol") == [("isOn", "table")]
    assert kb.models() == ["default", "bob", "carol"]
    kb.apply_models({"default": {"add": ["cup hasColor blue"]}})  # a functional property's new value replaces it
    assert kb["cup hasColor ?c"] == [{"c": "blue"}]


@pytest.mark.parametrize(("changes", "message"), [
    ({}, "mapping of model names"), (["bob"], "mapping of model names"),
    ({"all": {"add": ["a b c"]}}, "'all' is not one"), ({"bad name": {"add": ["a b c"]}}, "invalid model name"),
    ({"bob": ["a b c"]}, "must be {'add'"), ({"bob": {"added": ["a b c"]}}, "must be {'add'"),
    ({"bob": {"add": [1]}}, "statements must be strings"),
    ({"bob": {"add": ["a b c"]}, "default": {"add": ["only two"]}}, "only two"),
])
def test_apply_models_refuses_bad_changes_and_changes_nothing(kb: KB, changes: Any, message: str) -> None:
    revision = kb.revision
    with pytest.raises(KbError, match=re.escape(message)):
        kb.apply_models(changes)
    assert kb.models() == ["default"] and kb.revision == revision and kb.find("a b ?c") == []


# --- §3.5 writing ----------------------------------------------------------------------------


def test_add_is_update_and_operators(kb: KB) -> None:
    kb.add("cup hasColor red")
    kb.add("cup hasColor blue")  # add behaves as update: functional replacement
    assert kb["cup hasColor ?c"] == [{"c": "blue"}]
    kb += ["alfred sees cup"]
    kb -= ["alfred sees cup"]
    assert kb["alfred sees ?x"] == []


def test_remove_ground(kb: KB) -> None:
    kb += ["alfred sees cup", "alfred sees book"]
    kb.remove("alfred sees cup")
    assert kb["alfred sees ?x"] == [{"x": "book"}]
    kb.remove(["alfred sees book", "alfred sees nothing"])
    assert kb["alfred sees ?x"] == []


def test_retract_with_variables(kb: KB) -> None:
    kb += ["ari sees cup", "ari isIn kitchen", "ari rdf:type Robot", "bob sees cup"]
    kb -= "ari ?p ?o"
    assert kb["ari ?p ?o"] == []
    assert kb["?x sees cup"] == [{"x": "bob"}]
    kb += ["r1 rdf:type Robot", "r2 rdf:type Robot", "h1 rdf:type Human"]
    kb -= "?robot rdf:type Robot"
    assert kb["?r rdf:type Robot"] == []
    assert kb["?h rdf:type Human"] == [{"h": "h1"}]


def test_retract_a_conjunction(kb: KB) -> None:
    kb += ["r1 rdf:type Robot", "r1 sees ball", "r1 sees bat", "r3 rdf:type Robot", "h1 sees ball"]
    kb -= ["?x rdf:type Robot", "?x sees ?y"]  # K12
    assert kb["?x rdf:type Robot"] == [{"x": "r3"}]
    assert kb["?x sees ?y"] == [{"x": "h1", "y": "ball"}]


def test_retract_with_anonymous_variable(kb: KB) -> None:
    kb += ["alfred sees cup", "alfred sees book", "bob sees cup"]
    kb -= "alfred sees *"
    assert kb["?x sees ?y"] == [{"x": "bob", "y": "cup"}]


def test_retracting_an_inferred_only_triple_has_no_effect(kb: KB) -> None:
    kb += "alfred rdf:type Human"
    revision = kb.revision
    kb -= "alfred rdf:type Agent"
    assert kb["alfred rdf:type Agent"] == ["alfred rdf:type Agent"]
    assert kb.revision == revision
    kb -= "?x rdf:type foaf:Person"  # matches only inferred triples
    assert kb["alfred rdf:type Human"] == ["alfred rdf:type Human"]


def test_a_retraction_returns_the_number_of_asserted_triples_it_removed(kb: KB) -> None:
    kb += ["r1 rdf:type Robot", "r1 sees ball", "r1 sees bat", "r2 sees ball", "alfred rdf:type Human"]
    assert kb.remove("?x sees ball") == 2  # one pattern, two triples
    assert kb.remove(["r1 sees bat", "r1 sees nothing"]) == 1  # only what was asserted counts
    assert kb.remove("alfred rdf:type Agent") == 0  # inferred only: stays, nothing removed
    assert kb.revise(["?x rdf:type Robot"], {"method": "retract"}) == 1
    assert kb.revise(["r3 sees ball"], {"method": "add"}) is None
    kb += "r1 sees ball"
    assert kb.remove("r1 sees ball", models=["all"]) == 1


@pytest.mark.parametrize("method", ["add", "safe_add", "update", "safe_update", "revision", "ADD", "UPDATE"])
def test_revise_adding_methods(kb: KB, method: str) -> None:
    kb += "cup hasColor red"
    kb.revise(["cup hasColor blue", "alfred sees cup"], {"method": method})
    assert kb["cup hasColor ?c"] == [{"c": "blue"}]
    assert kb["alfred sees ?x"] == [{"x": "cup"}]


@pytest.mark.parametrize("method", ["retract", "remove", "RETRACT", "REMOVE", "DELETE"])
def test_revise_retracting_methods(kb: KB, method: str) -> None:
    kb += ["alfred sees cup", "alfred sees book"]
    kb.revise(["alfred sees cup"], {"method": method})
    assert kb["alfred sees ?x"] == [{"x": "book"}]
    kb.revise(["alfred sees ?x"], {"method": method})
    assert kb["alfred sees ?x"] == []


def test_revise_models(kb: KB) -> None:
    kb.revise(["alfred sees cup"], {"method": "add", "models": ["bob"]})
    assert kb.find("alfred sees ?x", models=["bob"]) == [{"x": "cup"}]
    assert kb["alfred sees ?x"] == []
    kb.revise(["alfred sees cup"], {"method": "retract", "models": ["bob"]})
    assert kb.find("alfred sees ?x", models=["bob"]) == []


@pytest.mark.parametrize("policy", [{}, {"method": "frobnicate"}, "add", None])
def test_revise_bad_policy(kb: KB, policy: Any) -> None:
    with pytest.raises(KbError):
        kb.revise(["alfred sees cup"], policy)
    assert kb["alfred sees ?x"] == []


# --- §3.7 housekeeping -----------------------------------------------------------------------


def test_hello_stats_methods(kb: KB) -> None:
    assert __version__ in kb.hello()
    assert kb.stats() == {"name": "situated", "version": __version__, "reasoning_enabled": True}
    methods = kb.methods()
    names = {m.split("(")[0] for m in methods}
    assert {
        "about", "add", "classesof", "clear", "details", "exist", "find", "hello", "label", "load",
        "lookup", "remove", "revise", "save", "sparql", "stats", "subscribe", "update",
    } <= names
    assert all(re.fullmatch(r"\w+\(.*\).*", m) for m in methods)
    find = next(m for m in methods if m.startswith("find("))
    assert find.index("patterns") < find.index("vars") < find.index("models")


def test_clear_keeps_the_ontology_by_default(kb: KB) -> None:
    kb += ["r1 rdf:type Robot", "alfred sees cup"]
    kb.add("x sees y", models=["bob"])
    kb.clear()
    assert kb.models() == ["default"]
    assert kb["alfred sees ?x"] == []
    assert kb["?x rdf:type Agent"] == [{"x": "myself"}]  # K5: the ontology is still there
    kb += "r1 rdf:type Robot"
    assert kb["?x rdf:type Agent"] == [{"x": "myself"}, {"x": "r1"}]


def test_clear_without_defaults_wipes_everything(kb: KB) -> None:
    kb.clear(keep_defaults=False)
    assert kb.size() == 0
    kb += "r1 rdf:type Robot"
    assert kb["?x rdf:type Agent"] == []


def test_kb_without_ontology() -> None:
    with KB(ontology=False) as k:
        assert k.size() == 0
        k += "r1 rdf:type Robot"
        assert k["?x rdf:type Agent"] == []


# --- reasoning seen through the facade ---------------------------------------------------------


def test_agents_include_humans_and_robots(kb: KB) -> None:
    kb += ["h1 rdf:type Human", "r1 rdf:type Robot", "p1 rdf:type foaf:Person", "cup1 rdf:type dbr:Cup"]
    assert kb["* rdf:type Agent"] == [{"var1": "h1"}, {"var1": "myself"}, {"var1": "p1"}, {"var1": "r1"}]
    assert kb["?x rdf:type foaf:Agent"] == kb["?x rdf:type Agent"]
    assert kb["?x rdf:type Human"] == [{"x": "h1"}, {"x": "p1"}]  # Human ≡ foaf:Person


def test_inverse_properties(kb: KB) -> None:
    kb += "cup isAt kitchen"
    assert kb["kitchen placeOf ?x"] == [{"x": "cup"}]
    kb += "table placeOf book"
    assert kb["book isAt ?x"] == [{"x": "table"}]
    kb += "box contains pen"
    assert kb["pen isContainedIn ?x"] == [{"x": "box"}]


def test_sub_properties(kb: KB) -> None:
    kb += ["cup isOn table", "pen isIn drawer"]
    assert kb["?x isAt ?y"] == [{"x": "cup", "y": "table"}, {"x": "pen", "y": "drawer"}]
    assert kb["table placeOf ?x"] == [{"x": "cup"}]


def test_symmetric_property(kb: KB) -> None:
    kb += "cup isNextTo plate"
    assert kb["plate isNextTo ?x"] == [{"x": "cup"}]


def test_transitive_property(kb: KB) -> None:
    kb += ["a1 leftOf a2", "a2 leftOf a3", "a3 leftOf a4"]
    assert kb["a1 leftOf ?x"] == [{"x": "a2"}, {"x": "a3"}, {"x": "a4"}]
    assert kb["a4 rightOf ?x"] == [{"x": "a1"}, {"x": "a2"}, {"x": "a3"}]  # inverse of a transitive one


def test_is_in_is_not_transitive(kb: KB) -> None:
    kb += ["cup isIn box", "box isIn kitchen"]
    assert kb["cup isIn ?x"] == [{"x": "box"}]


def test_domain_and_range(kb: KB) -> None:
    kb += "stranger sees thing"
    assert "foaf:Agent" in kb.classesof("stranger")
    assert "cyc:EnduringThing-Localized" in kb.classesof("thing")


def test_retraction_removes_derived_facts(kb: KB) -> None:
    kb += ["a1 leftOf a2", "a2 leftOf a3"]
    kb -= "a2 leftOf a3"
    assert kb["a1 leftOf ?x"] == [{"x": "a2"}]
    assert kb["a3 rightOf ?x"] == []
    kb += "cup isIn kitchen"
    kb -= "cup isIn kitchen"
    assert kb["kitchen placeOf ?x"] == []
    assert kb["cup isAt ?x"] == []


def test_retraction_keeps_facts_with_another_support(kb: KB) -> None:
    kb += ["d1 rdf:type Human", "d1 rdf:type Robot2", "Robot2 rdfs:subClassOf Agent"]
    kb -= "d1 rdf:type Human"
    assert kb["d1 rdf:type Agent"] == ["d1 rdf:type Agent"]
    kb += ["cup isIn kitchen", "cup isOn kitchen"]
    kb -= "cup isIn kitchen"
    assert kb["kitchen placeOf ?x"] == [{"x": "cup"}]
    kb += ["a1 leftOf a2", "a2 leftOf a3", "a1 leftOf a3"]
    kb -= "a2 leftOf a3"
    assert kb["a1 leftOf ?x"] == [{"x": "a2"}, {"x": "a3"}]


def test_tbox_change_through_the_facade(kb: KB) -> None:
    kb += "tom rdf:type Cat"
    assert kb["?x rdf:type Animal"] == []
    kb += "Cat rdfs:subClassOf Animal"
    assert kb["?x rdf:type Animal"] == [{"x": "tom"}]
    kb -= "Cat rdfs:subClassOf Animal"
    assert kb["?x rdf:type Animal"] == []


def test_is_asserted_and_size(kb: KB) -> None:
    size, asserted = kb.size(), kb.size(inferred=False)
    kb += "alfred rdf:type Human"
    assert kb.is_asserted("alfred rdf:type Human")
    assert not kb.is_asserted("alfred rdf:type Agent")
    assert kb.size(inferred=False) == asserted + 1
    assert kb.size() > size + 1


def test_a_write_naming_too_many_models_is_refused_and_creates_none() -> None:
    """Issue 19, item 9: the KB bounds the models one write names (each new one copies the closure)."""
    with KB(ontology=False, max_models_per_write=3) as kb:
        many = [f"m{i}" for i in range(4)]
        for write in (lambda: kb.add("a b c", models=many), lambda: kb.apply(["a b c"], [], many),
                      lambda: kb.remove("a b c", models=many), lambda: kb.load_data("<http://a> <http://b> <http://c> .", "nt", many),
                      lambda: kb.sparql_update("INSERT DATA { <http://a> <http://b> <http://c> }", many),
                      lambda: kb.revise(["a b c"], {"method": "add", "models": many}),
                      lambda: kb.apply_models({name: {"add": ["a b c"]} for name in many})):
            with pytest.raises(KbError, match="4 models in one write; the limit is 3"):
                write()
        assert kb.models() == ["default"] and kb.revision == 0
        kb.add("a b c", models=many[:3])
        assert sorted(kb.models()) == ["default", "m0", "m1", "m2"]
    assert KB(ontology=False)._max_models_per_write == 16  # the default bounds library users too
    with pytest.raises(KbError, match="positive integer"):
        KB(ontology=False, max_models_per_write=0)
