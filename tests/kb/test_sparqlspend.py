"""What a query's expressions may build (issue 26, item 1b): a chain of CONCATs that doubles a
string, a REPLACE that multiplies one and a GROUP_CONCAT gathering without end are stopped by
the string bounds with ``QueryTooLarge``, long before they take the memory they ask for; with
or without a deadline."""

from __future__ import annotations

import resource
import time
from collections.abc import Iterator

import pytest
from rdflib import Graph

from kb import KB
from kb.errors import QueryTooLarge
from kb.sparql import _GRAPH_ID, IndexStore, check_query
from kb.sparqlbudget import bound
from kb.sparqlspend import MAX_STRING, Spend

GENEROUS = 30.0


def doubling(times: int) -> str:
    """A 1 KB seed doubled ``times`` times: 1 GiB at 20 doublings, in under 1 KB of query (the
    tests stop at 4 MiB, so that a KB without the bound fails them rather than the machine)."""
    binds = " ".join(f"BIND(CONCAT(?v{i}, ?v{i}) AS ?v{i + 1})" for i in range(times))
    return f'SELECT (STRLEN(?v{times}) AS ?n) WHERE {{ BIND("{"x" * 1024}" AS ?v0) {binds} }}'


@pytest.fixture(scope="module")
def kb() -> Iterator[KB]:
    with KB() as k:
        yield k


def _rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


@pytest.mark.parametrize("timeout", [5.0, None], ids=["with a deadline", "without"])
def test_a_concat_chain_is_stopped_before_its_string_grows_past_the_bound(kb: KB, timeout: float | None) -> None:
    query = doubling(12)
    assert len(query) - 1024 < 1024
    before, start = _rss_mb(), time.monotonic()
    with pytest.raises(QueryTooLarge, match=r"CONCAT builds a string of \d+ characters; the limit is "
                                            f"{MAX_STRING} characters per string"):
        kb.sparql(query, timeout=timeout)
    assert time.monotonic() - start < GENEROUS
    assert _rss_mb() - before < 100, "the chain took 100 MB before it was stopped"


def test_strings_below_the_bound_are_built(kb: KB) -> None:
    assert kb.sparql(doubling(9))["results"]["bindings"][0]["n"]["value"] == str(1024 * 2**9)


def test_a_replace_that_multiplies_its_text_is_stopped(kb: KB) -> None:
    long = "y" * 5000
    query = (f'SELECT (STRLEN(?r) AS ?n) WHERE {{ BIND("{"x" * 5000}" AS ?t) '
             f'BIND(REPLACE(?t, "", "{long}") AS ?r) }}')
    with pytest.raises(QueryTooLarge, match="REPLACE builds a string"):
        kb.sparql(query, timeout=120)  # the spend stops it, not the clock (parsing alone is slow under load)
    assert kb.sparql('SELECT ?r WHERE { BIND(REPLACE("abc", "b", "$0$0") AS ?r) }')["results"][
        "bindings"][0]["r"]["value"] == "abbc"


def test_every_string_a_query_builds_counts_towards_its_total(kb: KB) -> None:
    # 40 rows, each keeping a 64 Ki string: 2.5 Mi characters, against a total of 1 Mi
    seed = "x" * 1024
    binds = " ".join(f"BIND(CONCAT(?v{i}, ?v{i}) AS ?v{i + 1})" for i in range(6))
    query = (f'SELECT ?v6 WHERE {{ VALUES ?k {{ {" ".join(map(str, range(40)))} }} '
             f'BIND(CONCAT("{seed}", STR(?k)) AS ?v0) {binds} }}')
    with KB() as small:
        checked = check_query(query)
        bound(checked.prepared, None, None, Spend(max_total=1 << 20))
        graph = Graph(store=IndexStore(small._one_model(None).closure), identifier=_GRAPH_ID)
        with pytest.raises(QueryTooLarge, match="build more than 1048576 characters of strings in all"):
            graph.query(checked.prepared).bindings  # noqa: B018


def test_group_concat_counts_every_value_it_keeps(kb: KB) -> None:
    query = ('SELECT (GROUP_CONCAT(?w) AS ?all) WHERE { VALUES ?a { 1 2 3 4 5 6 7 8 9 10 } '
             'VALUES ?b { 1 2 3 4 5 6 7 8 9 10 } BIND(CONCAT("word", STR(?a), STR(?b)) AS ?w) }')
    checked = check_query(query)
    bound(checked.prepared, None, None, Spend(max_total=500))
    graph = Graph(store=IndexStore(kb._one_model(None).closure), identifier=_GRAPH_ID)
    with pytest.raises(QueryTooLarge, match="GROUP_CONCAT"):
        graph.query(checked.prepared).bindings  # noqa: B018
    words = kb.sparql(query)["results"]["bindings"][0]["all"]["value"].split()
    assert len(words) == 100 and "word105" in words
