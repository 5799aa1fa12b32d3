"""Pattern queries (kb-compat §1.5, §3.2): projection rules, the join, distinct rows, and the fact
that the find path never goes through rdflib's SPARQL engine or any Turtle/SPARQL text.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator

import pytest
import rdflib
import rdflib.plugins.sparql.parser
import rdflib.plugins.sparql.processor
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from rdflib import BNode, Literal, URIRef, Variable

import kb.sparql
from kb import KB, KbError
from kb.index import TripleIndex
from kb.query import build_query, holds, rows, solve
from kb.terms import format_term, parse_patterns
from kb.unicode import carried

ORO = "http://kb.openrobots.org#"


def o(name: str) -> URIRef:
    return URIRef(ORO + name)


# --- projection (§1.5) -----------------------------------------------------------------------


@pytest.mark.parametrize(
    ("patterns", "vars", "names"),
    [
        (["myself sees ?obj"], None, ("obj",)),
        (["?h sees ?o", "?o rdf:type dbr:Cup", "?h rdf:type Human"], None, ("h", "o")),
        (["* sees *"], None, ("var1", "var2")),
        (["* sees *", "* isIn kitchen"], None, ("var1", "var2", "var3")),
        (["?agent looksAt *"], None, ("agent",)),
        (["* looksAt ?thing", "?agent sees *"], None, ("thing", "agent")),
        (["?a sees ?b"], ["?b"], ("b",)),
        (["?a sees ?b"], ["b", "a"], ("b", "a")),
        (["?a sees ?b"], ["?a", "?b"], ("a", "b")),
        (["myself sees cup"], None, ()),
        # knowledge_core's anonymous variables: any whose name starts with '__' (its clients
        # write every '*' as one), named var1, var2... when there is no named variable.
        (["?__ rdfs:subClassOf Agent"], None, ("var1",)),
        (["?__a ?__b ?__c"], ["?__a", "?__b", "?__c"], ("var1", "var2", "var3")),
        (["?__b likes ?__a"], ["?__a", "?__b"], ("var1", "var2")),
        (["?x likes ?__y"], None, ("x",)),
        (["?x ?__p ?__y"], ["?x", "?__p"], ("x",)),
        (["?__x likes *"], None, ("var1", "var2")),
    ],
)
def test_projection_rules(patterns: list[str], vars: list[str] | None, names: tuple[str, ...]) -> None:
    assert build_query(parse_patterns(patterns), vars).names == names


def test_ground_query_is_flagged() -> None:
    assert build_query(parse_patterns(["myself sees cup"])).ground
    assert not build_query(parse_patterns(["myself sees ?x"])).ground


def test_vars_must_occur_in_the_patterns() -> None:
    with pytest.raises(KbError, match=r"\?zz"):
        build_query(parse_patterns(["?a sees ?b"]), ["?zz"])


# --- the join --------------------------------------------------------------------------------


def index_of(*triples: tuple[str, str, str]) -> TripleIndex:
    index = TripleIndex()
    for s, p, obj in triples:
        index.add(o(s), o(p), o(obj))
    return index


WORLD = [
    ("alice", "sees", "cup1"),
    ("alice", "sees", "book1"),
    ("bob", "sees", "cup1"),
    ("robot", "sees", "cup2"),
    ("cup1", "type", "Cup"),
    ("cup2", "type", "Cup"),
    ("book1", "type", "Book"),
    ("alice", "type", "Human"),
    ("bob", "type", "Human"),
    ("robot", "type", "Robot"),
    ("alice", "knows", "alice"),
    ("alice", "knows", "bob"),
]


def brute_force(
    triples: list[tuple[str, str, str]], patterns: list[tuple[str, str, str]]
) -> set[tuple[str, ...]]:
    variables = sorted({t for pattern in patterns for t in pattern if t.startswith("?")})
    constants = {t for triple in triples for t in triple}
    found = set()
    for values in itertools.product(sorted(constants), repeat=len(variables)):
        binding = dict(zip(variables, values, strict=True))
        if all(tuple(binding.get(t, t) for t in pattern) in set(triples) for pattern in patterns):
            found.add(tuple(binding[v] for v in variables))
    return found


@pytest.mark.parametrize(
    "patterns",
    [
        [("?h", "sees", "?o"), ("?o", "type", "Cup"), ("?h", "type", "Human")],
        [("?x", "knows", "?x")],
        [("?x", "knows", "?y"), ("?y", "sees", "?o")],
        [("?x", "?p", "cup1")],
        [("alice", "?p", "?o")],
        [("?a", "sees", "?o"), ("?b", "sees", "?o")],
        [("?x", "type", "Robot"), ("?x", "type", "Human")],
    ],
)
def test_join_matches_brute_force(patterns: list[tuple[str, str, str]]) -> None:
    index = index_of(*WORLD)
    parsed = [tuple(Variable(t[1:]) if t.startswith("?") else o(t) for t in p) for p in patterns]
    variables = sorted({t for p in patterns for t in p if t.startswith("?")})
    query = build_query(parsed, variables)  # type: ignore[arg-type]
    got = {tuple(str(t)[len(ORO):] for t in row) for row in rows(index, query)}
    assert got == brute_force(WORLD, patterns)
    assert holds(index, query) == bool(got)


def test_repeated_variable_in_one_pattern() -> None:
    index = index_of(*WORLD)
    bindings = list(solve(index, parse_patterns(["?x knows ?x"])))
    assert bindings == [{Variable("x"): o("alice")}]


def test_rows_are_distinct_after_projection() -> None:
    index = index_of(("alfred", "looksAt", "a1"), ("alfred", "looksAt", "a2"), ("bob", "looksAt", "a1"))
    query = build_query(parse_patterns(["?agent looksAt *"]))
    assert rows(index, query) == {(o("alfred"),), (o("bob"),)}


def test_rows_with_blank_nodes_are_dropped() -> None:
    index = TripleIndex()
    index.add(BNode(), o("sees"), o("cup"))
    index.add(o("alice"), o("sees"), o("cup"))
    assert rows(index, build_query(parse_patterns(["?x sees cup"]))) == {(o("alice"),)}


def test_solve_on_missing_terms_is_empty() -> None:
    index = index_of(*WORLD)
    assert list(solve(index, parse_patterns(["?x sees nothing_here"]))) == []
    assert not holds(index, build_query(parse_patterns(["?x sees ?y", "?y type Unicorn"])))


# --- the find path never uses SPARQL or Turtle text -------------------------------------------


def _refuse(*args: object, **kwargs: object) -> None:
    raise AssertionError("the find path must not parse SPARQL or RDF text")


@pytest.fixture
def no_text_parsing(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    monkeypatch.setattr(rdflib.plugins.sparql.processor, "prepareQuery", _refuse)
    monkeypatch.setattr(rdflib.plugins.sparql.processor, "parseQuery", _refuse)
    monkeypatch.setattr(rdflib.plugins.sparql.parser, "parseQuery", _refuse)
    monkeypatch.setattr(rdflib.plugins.sparql, "prepareQuery", _refuse)
    for name in ("prepareQuery", "parseQuery", "translateQuery"):
        monkeypatch.setattr(kb.sparql, name, _refuse, raising=False)
    monkeypatch.setattr(rdflib.Graph, "query", _refuse)
    monkeypatch.setattr(rdflib.Graph, "update", _refuse)
    monkeypatch.setattr(rdflib.Graph, "parse", _refuse)
    yield


@pytest.fixture(scope="module")
def shared_kb() -> Iterator[KB]:
    with KB() as k:
        yield k


def test_the_guard_does_block_sparql(shared_kb: KB, no_text_parsing: None) -> None:
    with pytest.raises(AssertionError, match="must not parse"):
        shared_kb.sparql("ASK { ?s ?p ?o }")
    with pytest.raises(AssertionError, match="must not parse"):
        shared_kb.load_data("<http://a/b> <http://a/c> <http://a/d> .", "turtle")  # N-Triples is read without rdflib


INJECTION_TEXTS = [
    '"x" } ; DROP ALL ; SELECT * WHERE { ?s ?p ?o',
    'x" . ?s ?p ?o . FILTER(true) #',
    '> <http://evil/> <http://evil/> . #',
    '""" } UNION { ?s ?p ?o } """',
    "\\\" ; INSERT DATA { <a> <b> <c> }",
]


@pytest.mark.parametrize("content", INJECTION_TEXTS)
def test_injection_attempts_are_plain_literals(shared_kb: KB, no_text_parsing: None, content: str) -> None:
    literal = format_term(Literal(content))
    shared_kb += f"inj_subject note {literal}"
    assert shared_kb["inj_subject note ?v"] == [{"v": content}]
    assert shared_kb[f"?x note {literal}"] == [{"x": "inj_subject"}]
    assert shared_kb.exist([f"inj_subject note {literal}"])
    shared_kb -= f"inj_subject note {literal}"
    assert shared_kb["inj_subject note ?v"] == []


@pytest.mark.parametrize(
    "pattern",
    [
        "?s ?p ?o } ; DROP ALL ; SELECT * WHERE { ?s ?p ?o",
        '?s <http://x> "a" . ?s ?p ?o',
        "?s ?p ?o . ?a ?b ?c",
    ],
)
def test_pattern_text_with_extra_syntax_is_refused(
    shared_kb: KB, no_text_parsing: None, pattern: str
) -> None:
    before = shared_kb.size(inferred=False)
    with pytest.raises(KbError):
        shared_kb.find(pattern)
    with pytest.raises(KbError):
        shared_kb.add(pattern.replace("?", "v"))
    assert shared_kb.size(inferred=False) == before


_FIRST = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ_"
names = st.builds(
    lambda first, middle, last: first + middle + last,
    st.sampled_from(_FIRST),
    st.text(alphabet=_FIRST + "0123456789()-._", max_size=10),
    st.text(alphabet=_FIRST + "0123456789()-_", max_size=1),
).filter(lambda n: n not in ("a", "true", "false") and not n.endswith("."))
# Any text, with the characters that matter to the tokeniser made frequent.
_TRICKY = ['"', "\\", "'", "\n", "\r", "\t", '"""', "@en", "^^xsd:integer", "\\u00e9", " ", ".", "?x", "*"]
# Lone surrogates are not text the KB takes (kb.unicode refuses them; tests/kb/test_unicode.py).
# Text the KB takes (kb.unicode: no lone surrogate, no C0 control RDF/XML cannot carry).
texts = st.lists(st.one_of(st.characters(exclude_categories=("Cs",)), st.sampled_from(_TRICKY)),
                 max_size=30).map("".join).map(carried)
# (what a client writes, what find must return for it)
written_values = st.one_of(
    names.map(lambda n: (n, n)),
    st.tuples(st.sampled_from(["dbr", "cyc", "foaf"]), names).map(lambda pn: (f"{pn[0]}:{pn[1]}",) * 2),
    texts.map(lambda t: (format_term(Literal(t)), t)),
    st.integers(min_value=-(10**9), max_value=10**9).map(lambda i: (str(i), i)),
    st.floats(allow_nan=False, allow_infinity=False).map(lambda f: (repr(f), f)),
    st.booleans().map(lambda b: (str(b).lower(), b)),
)
_counter = itertools.count()


@settings(suppress_health_check=[HealthCheck.function_scoped_fixture], max_examples=80, deadline=None)
@given(subject=names, pair=written_values)
def test_add_then_find_returns_the_written_value(
    shared_kb: KB, no_text_parsing: None, subject: str, pair: tuple[str, object]
) -> None:
    written, expected = pair
    subj = f"{subject}_{next(_counter)}"
    shared_kb += f"{subj} hval {written}"
    try:
        found = shared_kb[f"{subj} hval ?v"]
        assert found == [{"v": expected}]
        assert type(found[0]["v"]) is type(expected)
        # What came back is usable in a later pattern (§1.7 round trip).
        again = found[0]["v"] if isinstance(expected, str) and written == expected else written
        assert shared_kb[f"?s hval {again}"] == [{"s": subj}]
        assert f"{subj} hval {written}" in shared_kb
    finally:
        shared_kb -= f"{subj} hval ?v"
    assert shared_kb[f"{subj} hval ?v"] == []


# --- hypothesis: the join equals a brute-force evaluation -------------------------------------

_CONSTANTS = ["alice", "bob", "cup1", "cup2"]
_PREDICATES = ["sees", "knows", "type"]
world_triples = st.lists(
    st.tuples(st.sampled_from(_CONSTANTS), st.sampled_from(_PREDICATES), st.sampled_from(_CONSTANTS)),
    max_size=25,
)
pattern_terms = st.sampled_from(["?a", "?b", "?c", *_CONSTANTS])
pattern_lists = st.lists(
    st.tuples(pattern_terms, st.sampled_from(["?p", *_PREDICATES]), pattern_terms), min_size=1, max_size=3
)


@settings(max_examples=150, deadline=None)
@given(world_triples, pattern_lists)
def test_random_conjunctions_match_brute_force(
    triples: list[tuple[str, str, str]], patterns: list[tuple[str, str, str]]
) -> None:
    index = index_of(*triples)
    parsed = [tuple(Variable(t[1:]) if t.startswith("?") else o(t) for t in p) for p in patterns]
    variables = sorted({t for p in patterns for t in p if t.startswith("?")})
    expected = brute_force(sorted(set(triples)), patterns)
    if not variables:
        assert holds(index, build_query(parsed)) == all(p in set(triples) for p in patterns)  # type: ignore[arg-type]
        return
    query = build_query(parsed, variables)  # type: ignore[arg-type]
    got = {tuple(str(t)[len(ORO):] for t in row) for row in rows(index, query)}
    assert got == expected


def test_max_rows_stops_a_query_with_too_many_rows() -> None:
    import pytest

    from kb import KB
    from kb.errors import TooManyRows

    with KB() as kb:
        kb += [f"myself sees thing_{i}" for i in range(20)]
        assert len(kb.find("myself sees ?x", max_rows=20)) == 20
        with pytest.raises(TooManyRows, match="more than 19 rows"):
            kb.find("myself sees ?x", max_rows=19)
        with pytest.raises(TooManyRows):
            kb.find(["myself sees ?x", "myself sees ?y"], max_rows=100)
