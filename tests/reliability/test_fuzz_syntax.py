"""Property tests of the statement and pattern syntax through the HTTP API (``/kb/revise`` and
``/kb/query`` on a live server): random literals, numbers and names round-trip exactly, and no
input, however crafted, adds more than the one triple a statement stands for or changes the KB
when it is refused. Statements are parsed into terms, never pasted into SPARQL or Turtle, so text
like ``"} ; DROP ALL`` or ``> . <x> <y> <z`` must stay inside its literal."""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from typing import Any

import hypothesis
import pytest
from hypothesis import example, given
from hypothesis import strategies as st

from api.app import create_app
from api.settings import Settings
from kb.unicode import carried
from tests.api.conftest import Live, serve

SETTINGS = hypothesis.settings(max_examples=150, deadline=None, derandomize=True,
                               suppress_health_check=[hypothesis.HealthCheck.function_scoped_fixture])
NAME = r"\w(?:[\w\-.()~!$&+,;=/%]*[\w\-()~!$&+,;=/%])?"
INJECTIONS = ['"} ; DROP ALL ; INSERT DATA { <x> <y> <z> } #', "> . <x> <y> <z", 'a\nb" . x y z . "',
              "x' ; y z w . '", '\\" . evil owns robot . "', "\\", '"""', "@en ^^xsd:int", "?s ?p ?o",
              "\x7f\r\n\t\u2028\x85", "SELECT * WHERE { ?s ?p ?o }"]
_ids = itertools.count()


@pytest.fixture(scope="module")
def live() -> Iterator[Live]:
    with serve(create_app(Settings(scene="none"))) as server:
        yield server


def quoted(text: str) -> str:
    """A string literal in statement syntax (N3 escapes)."""
    escaped = text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n").replace("\r", "\\r")
    return f'"{escaped}"'


def asserted(live: Live) -> int:
    count: int = live.client.get("/health").json()["kb"]["asserted"]
    return count


def add(live: Live, statement: str) -> Any:
    return live.client.post("/kb/revise", json={"method": "add", "statements": [statement]})


def query(live: Live, *patterns: str) -> list[dict[str, Any]]:
    response = live.client.post("/kb/query", json={"patterns": list(patterns)})
    assert response.status_code == 200, response.text
    rows: list[dict[str, Any]] = response.json()
    return rows


def fresh() -> str:
    return f"fuzz_{next(_ids)}"


@SETTINGS
@given(text=st.text())
@example(text="")
def test_string_literals_round_trip_as_one_triple(live: Live, text: str) -> None:
    subject, predicate, before = fresh(), fresh(), asserted(live)
    response = add(live, f"{subject} {predicate} {quoted(text)}")
    if carried(text) != text:  # a control character RDF/XML cannot carry: refused, nothing written
        assert response.status_code == 400 and "cannot carry" in response.json()["message"], response.text
        assert asserted(live) == before
        return
    assert response.status_code == 200, response.text
    assert asserted(live) == before + 1
    assert query(live, f"{subject} ?p ?v") == [{"p": predicate, "v": text}]
    assert query(live, f"?s {predicate} {quoted(text)}") == [{"s": subject}]


@pytest.mark.parametrize("text", INJECTIONS)
def test_injection_attempts_stay_one_literal(live: Live, text: str) -> None:
    subject, before = fresh(), asserted(live)
    assert add(live, f"{subject} probeValue {quoted(text)}").status_code == 200
    assert asserted(live) == before + 1
    assert query(live, f"{subject} ?p ?v") == [{"p": "probeValue", "v": text}]
    assert query(live, "x y ?z") == [] and query(live, "evil owns ?z") == []


@SETTINGS
@given(text=st.text().map(carried), lang=st.from_regex(r"[a-z]{2}(-[A-Z]{2})?", fullmatch=True))
def test_language_tagged_literals_round_trip(live: Live, text: str, lang: str) -> None:
    subject = fresh()
    assert add(live, f"{subject} probeValue {quoted(text)}@{lang}").status_code == 200
    assert query(live, f"{subject} probeValue ?v") == [{"v": text}]


@SETTINGS
@given(number=st.integers(min_value=-(10**30), max_value=10**30)
       | st.floats(allow_nan=False, allow_infinity=False))
def test_numbers_round_trip(live: Live, number: float) -> None:
    subject = fresh()
    assert add(live, f"{subject} probeValue {number!r}").status_code == 200
    (row,) = query(live, f"{subject} probeValue ?v")
    assert row["v"] == number and type(row["v"]) is type(number)


def _plain_name(name: str) -> bool:
    # Words that read as something else: numbers and booleans are literals, `a` is rdf:type.
    words = name.replace("+", "").replace("-", "").replace(".", "", 1).replace("e", "", 1).replace("E", "", 1)
    return not words.isdigit() and name not in ("true", "false", "a")


@SETTINGS
@given(subject=st.from_regex(NAME, fullmatch=True).filter(_plain_name),
       target=st.from_regex(NAME, fullmatch=True).filter(_plain_name))
def test_names_round_trip(live: Live, subject: str, target: str) -> None:
    predicate = fresh()
    response = add(live, f"{subject} {predicate} {target}")
    assert response.status_code == 200, response.text
    assert query(live, f"?s {predicate} ?o") == [{"s": subject, "o": target}]


@SETTINGS
@given(statement=st.text() | st.lists(st.sampled_from(['"', "'", "<", ">", " ", ".", "\\", "?x", "*", "a",
                                                       "b", "@en", "^^", "x:y", "\n", "{", "}", ";"]),
                                       max_size=12).map("".join))
@example(statement='s p "o" . s2 p2 o2')
@example(statement="s p <o> . <s2> <p2> <o2>")
@example(statement='s p "unterminated')
def test_any_statement_adds_at_most_one_triple_or_is_refused_cleanly(live: Live, statement: str) -> None:
    before = asserted(live)
    response = add(live, statement)
    after = asserted(live)
    if response.status_code == 200:
        assert after - before in (0, 1), (statement, after - before)  # 0: it was already there
    else:
        body = response.json()
        assert response.status_code in (400, 422) and body["message"], body
        assert after == before, statement  # nothing half-written
    patterns = live.client.post("/kb/query", json={"patterns": [statement]})
    assert patterns.status_code in (200, 400, 422), patterns.text
    assert asserted(live) == after  # a query never writes
