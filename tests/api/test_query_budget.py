"""Over HTTP and the CLI (issue 19, item 8): one anonymous query cannot lock the service.

A cartesian SPARQL COUNT, a catastrophic regex and a join without end answer 503 query_timeout
at the service's budget; a huge SELECT answers 413 too_many_rows; while such a query runs, a
write and /health complete. Bounds on time are generous: they tell "stopped at the budget" from
"ran for minutes".
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterator
from typing import Any

import httpx
import pytest

from api.cli import main
from api.settings import Limits, Settings
from kb import KB
from tests.api.conftest import SCENE, Live

GENEROUS = 30.0
CARTESIAN_COUNT = "SELECT (COUNT(*) AS ?n) WHERE { ?a ?b ?c . ?d ?e ?f }"
EVIL_REGEX = 'SELECT ?x WHERE { BIND("' + "a" * 40 + 'b" AS ?x) FILTER(REGEX(?x, "(a|aa)+$")) }'


@pytest.fixture(scope="module")
def big_kb() -> Iterator[KB]:
    with KB() as kb:
        kb += [f"thing_{i} isOn table_{i % 7}" for i in range(1500)]
        yield kb


@pytest.fixture
def live(live_factory: Callable[..., Live], big_kb: KB) -> Live:
    settings = Settings(scene=SCENE, limits=Limits(query_timeout=1.0, max_rows=1000))
    return live_factory(settings, kb=big_kb)


@pytest.fixture
def capped(live_factory: Callable[..., Live], big_kb: KB) -> Live:
    """Only the row cap binds: on a loaded machine the 1 s budget could stop a query first."""
    settings = Settings(scene=SCENE, limits=Limits(query_timeout=GENEROUS, max_rows=1000))
    return live_factory(settings, kb=big_kb)


def client(live: Live) -> httpx.Client:
    return httpx.Client(base_url=live.url, timeout=GENEROUS)


def test_a_cartesian_count_answers_query_timeout(live: Live) -> None:
    with client(live) as http:
        answer = http.get("/sparql", params={"query": CARTESIAN_COUNT})
    assert answer.status_code == 503
    body = answer.json()
    assert (body["status"], body["code"], body["details"]) == (503, "query_timeout", {"timeout": 1.0})
    assert "time budget of 1 s" in body["message"]


def test_a_catastrophic_regex_answers_query_timeout(live: Live) -> None:
    with client(live) as http:
        answer = http.post("/sparql", content=EVIL_REGEX, headers={"content-type": "application/sparql-query"})
        assert answer.json()["code"] == "query_timeout"
        bad = http.get("/sparql", params={"query": "SELECT * WHERE { FILTER(REGEX('a', '(')) }"})
        assert (bad.status_code, bad.json()["code"]) == (400, "kb_error")
        assert "invalid regular expression" in bad.json()["message"]


def test_a_huge_select_answers_too_many_rows(capped: Live) -> None:
    with client(capped) as http:
        for accept in ("application/sparql-results+json", "text/tab-separated-values"):
            answer = http.get("/sparql", params={"query": "SELECT * WHERE { ?a ?b ?c . ?d ?e ?f }"},
                              headers={"accept": accept})
            assert answer.status_code == 413
            assert answer.json() | {"message": ""} == {"status": 413, "code": "too_many_rows", "message": "",
                                                       "details": {"limit": 1000}}


def test_a_join_without_end_answers_query_timeout(live: Live) -> None:
    with client(live) as http:
        answer = http.post("/kb/query", json={"patterns": ["?a ?b ?c", "?d ?e ?f"], "vars": ["?b"]})
    assert (answer.status_code, answer.json()["code"]) == (503, "query_timeout")


def test_writes_and_health_go_on_while_a_query_runs(live: Live) -> None:
    outcome: list[Any] = []

    def run_query() -> None:
        with client(live) as http:
            outcome.append(http.get("/sparql", params={"query": CARTESIAN_COUNT}).json()["code"])

    query = threading.Thread(target=run_query)
    query.start()
    try:
        time.sleep(0.3)  # the query has the KB now
        with client(live) as http:
            start = time.monotonic()
            health = http.get("/health")
            write = http.post("/kb/revise", json={"statements": ["thing_2 isOn shelf_9"], "method": "add"})
            took = time.monotonic() - start
        assert health.status_code == 200 and write.status_code == 200
        assert took < GENEROUS
    finally:
        query.join(GENEROUS)
    assert outcome == ["query_timeout"]


def test_the_cli_applies_the_limits_in_process(monkeypatch: pytest.MonkeyPatch,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setenv("SITUATED_LIMITS__MAX_ROWS", "3")
    assert main(["kb", "query", "?s ?p ?o", "--scene", str(SCENE)]) == 2
    assert "more than 3 rows" in capsys.readouterr().err
    monkeypatch.setenv("SITUATED_LIMITS__MAX_ROWS", "100000000")
    monkeypatch.setenv("SITUATED_LIMITS__QUERY_TIMEOUT", "0.2")
    start = time.monotonic()
    assert main(["kb", "query", "?a ?b ?c", "?d ?e ?f", "--scene", str(SCENE)]) == 2
    assert "time budget of 0.2 s" in capsys.readouterr().err
    assert time.monotonic() - start < 10 * GENEROUS
