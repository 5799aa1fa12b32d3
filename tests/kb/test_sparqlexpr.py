"""A SPARQL expression's errors are error values, never a server error, and its numbers are
bounded (issue 26, the rerun of attack 1b): each query below raised a Python error out of rdflib
(a 500), and CEIL of a decimal of a million digits held the GIL for 78 s."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest

from kb import KB
from kb.errors import QueryEvaluationError
from kb.sparqlexpr import MAX_DIGITS

X = "PREFIX xsd: <http://www.w3.org/2001/XMLSchema#> "
HUGE = '"1E999999"^^xsd:decimal'

# One expression of each kind of failure the rerun found, each valid SPARQL over valid RDF terms.
FAILING = {
    "decimal overflow": f"{HUGE} * 10",
    "decimal sum overflow": f'{HUGE} + "9E999999"^^xsd:decimal',
    "ROUND of a huge decimal": f"ROUND({HUGE})",
    "CEIL of a huge decimal": f"CEIL({HUGE})",
    "FLOOR of a huge decimal": f"FLOOR({HUGE})",
    "a huge decimal cast to an integer": f"xsd:integer({HUGE})",
    "CEIL of INF": 'CEIL(xsd:double("INF"))',
    "ROUND of INF": 'ROUND(xsd:double("INF"))',
    "ROUND of NaN": 'ROUND(xsd:double("NaN"))',
    "SUBSTR from NaN": 'SUBSTR("abc", "NaN"^^xsd:double)',
    "SUBSTR of INF characters": 'SUBSTR("abc", 1, 1E400)',
    "REPLACE with a group the pattern lacks": 'REPLACE("a", "(a)", "\\\\9")',
    "dateTime plus a duration past year 9999":
        'xsd:dateTime("9999-12-31T23:59:59Z") + xsd:dayTimeDuration("P1D")',
    "dateTime minus a huge duration": '"2024-01-01T00:00:00Z"^^xsd:dateTime - "P99999999999D"^^xsd:duration',
    "date plus a huge duration": '"2024-01-01"^^xsd:date + "P99999999999D"^^xsd:dayTimeDuration',
    "naive minus aware dateTime":
        '"2024-01-01T00:00:00"^^xsd:dateTime - "2024-01-01T00:00:00+01:00"^^xsd:dateTime',
    "MONTH of an invalid dateTime": 'MONTH("2024-13-45T99:99:99"^^xsd:dateTime)',
    "an integer from a hexBinary": 'xsd:integer("1"^^xsd:hexBinary)',
}


@pytest.fixture(scope="module")
def kb() -> Iterator[KB]:
    with KB() as k:
        yield k


def _rows(kb: KB, query: str) -> list[dict[str, Any]]:
    rows: list[dict[str, Any]] = kb.sparql(X + query)["results"]["bindings"]
    return rows


@pytest.mark.parametrize("expression", list(FAILING.values()), ids=list(FAILING))
def test_an_expression_that_fails_is_unbound_in_a_projection(kb: KB, expression: str) -> None:
    assert _rows(kb, f"SELECT (({expression}) AS ?x) (1 AS ?one) WHERE {{}}") == [
        {"one": {"type": "literal", "value": "1",
                 "datatype": "http://www.w3.org/2001/XMLSchema#integer"}}]
    # Before: CEIL, FLOOR and the cast held the GIL 78 s or more, no deadline could stop them.


@pytest.mark.parametrize("expression", list(FAILING.values()), ids=list(FAILING))
def test_an_expression_that_fails_makes_a_filter_false_and_a_bind_unbound(kb: KB, expression: str) -> None:
    assert _rows(kb, f"SELECT ?v WHERE {{ VALUES ?v {{ 1 }} FILTER(({expression}) || true) }}")
    assert _rows(kb, f"SELECT ?v WHERE {{ VALUES ?v {{ 1 }} FILTER(({expression}) = ({expression})) }}") == []
    rows = _rows(kb, f"SELECT ?v ?x WHERE {{ VALUES ?v {{ 1 }} BIND(({expression}) AS ?x) }}")
    assert [set(row) for row in rows] == [{"v"}]


def test_a_huge_number_from_the_data_is_bounded_as_a_constant_is(kb: KB) -> None:
    assert _rows(kb, f"SELECT (CEIL(?d) AS ?x) WHERE {{ VALUES ?d {{ {HUGE} }} }}") == [{}]


def test_numbers_below_the_bound_are_computed_exactly(kb: KB) -> None:
    largest = f'"1E{MAX_DIGITS - 1}"^^xsd:decimal'
    (row,) = _rows(kb, f"SELECT (CEIL({largest}) AS ?x) (1.5 * 2 AS ?y) WHERE {{}}")
    assert row["x"]["value"] == "1" + "0" * (MAX_DIGITS - 1)
    assert row["y"]["value"] == "3.0"
    # A result that reaches the bound is an error value, so the next step never sees it.
    assert _rows(kb, f"SELECT (CEIL({largest} * 10) AS ?x) WHERE {{}}") == [{}]


@pytest.mark.parametrize("aggregate", [
    'SUM(?x) WHERE { VALUES ?x { "P1D"^^xsd:dayTimeDuration 1 } }',
    'SUM(?x) WHERE { VALUES ?x { "9E999999"^^xsd:decimal "9E999999"^^xsd:decimal } }',
    'AVG(?x) WHERE { VALUES ?x { "9E999999"^^xsd:decimal "9E999999"^^xsd:decimal } }',
], ids=["a duration and a number", "decimals past the largest", "their average"])
def test_an_aggregate_that_fails_is_refused_clearly(kb: KB, aggregate: str) -> None:
    select, where = aggregate.split(" WHERE ")
    with pytest.raises(QueryEvaluationError, match="the query could not be evaluated: "):
        kb.sparql(X + f"SELECT ({select} AS ?s) WHERE {where}")
