"""Over HTTP and the CLI (issue 19, item 8): one anonymous query cannot lock the service.

A cartesian SPARQL COUNT, a catastrophic regex and a join without end answer 503 query_timeout
at the service's budget; a huge SELECT answers 413 too_many_rows; while such a query runs, a
write and /health complete. Bounds on time are generous: they tell "stopped at the budget" from
"ran for minutes".
"""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Callable, Iterator
from typing import Any

import httpx
import pytest
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

from api.cli import main
from api.settings import Limits, Settings
from kb import KB
from tests.api.conftest import SCENE, Live
from tests.waiting import until

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


# --- subscriptions: /kb/events and /kb/events/ws -------------------------------------------------

def _events(response: httpx.Response) -> Iterator[tuple[str, Any]]:
    """(event name, decoded data) pairs of an SSE stream."""
    name = "message"
    for line in response.iter_lines():
        if line.startswith("event:"):
            name = line[6:].strip()
        elif line.startswith("data:"):
            yield name, json.loads(line[5:])
            name = "message"


SLOW_FEW_ROWS = ["* ?p *", "* ?q *", "* * *"]  # pairs of predicates: few rows, n³ steps


def test_a_subscription_past_the_limits_is_refused(live: Live, big_kb: KB) -> None:
    subscriptions = len(big_kb.writer.subscriptions)
    with client(live) as http:
        slow = http.get("/kb/events", params={"pattern": SLOW_FEW_ROWS})
        assert slow.status_code == 503
        assert (slow.json()["code"], slow.json()["details"]) == ("query_timeout", {"timeout": 1.0})
        huge = http.get("/kb/events", params={"pattern": ["?a isOn ?t"]})
        assert (huge.status_code, huge.json()["code"], huge.json()["details"]) == (413, "too_many_rows",
                                                                                 {"limit": 1000})
    for patterns, code in ((SLOW_FEW_ROWS, "query_timeout"), (["?a isOn ?t"], "too_many_rows")):
        with connect(live.ws_url + "/kb/events/ws") as ws:
            ws.send(json.dumps({"patterns": patterns}))
            assert json.loads(ws.recv(timeout=GENEROUS))["code"] == code
            with pytest.raises(ConnectionClosed) as closed:
                ws.recv(timeout=GENEROUS)
            assert closed.value.rcvd is not None and closed.value.rcvd.code == 1008
    assert len(big_kb.writer.subscriptions) == subscriptions
    until(lambda: live.services.hub.listener_count == 0)


def _cartesian(trigger: str) -> list[str]:
    """No row nor work until ``<trigger> isOn ...`` holds; then few rows after n³ steps."""
    return [f"{trigger} isOn ?z", *SLOW_FEW_ROWS]


def test_a_live_subscription_past_the_budget_is_ended_with_the_error(live: Live, big_kb: KB) -> None:
    with client(live) as http, http.stream("GET", "/kb/events",
                                           params={"pattern": _cartesian("trigger_sse")}) as response:
        events = _events(response)
        assert next(events)[0] == "subscribed"
        with client(live) as writer:
            start = time.monotonic()
            write = writer.post("/kb/revise", json={"statements": ["trigger_sse isOn shelf_1"], "method": "add"})
            assert write.status_code == 200 and time.monotonic() - start < 10.0  # the budget is 1 s
        name, error = next(events)
        assert name == "error" and error["status"] == 503 and error["code"] == "query_timeout"
        assert error["details"] == {"timeout": 1.0} and "time budget of 1 s" in error["message"]
        assert list(events) == []  # the stream ends there
    until(lambda: live.services.hub.listener_count == 0)


def test_a_live_websocket_subscription_past_the_row_cap_is_ended_with_the_error(live: Live) -> None:
    with connect(live.ws_url + "/kb/events/ws") as ws:
        ws.send(json.dumps({"patterns": ["?x isOn shelf_ws", "?x isOn ?t"]}))
        assert "subscribed" in json.loads(ws.recv(timeout=GENEROUS))
        with client(live) as writer:
            for start in (0, 600):
                statements = [f"item_{i} isOn shelf_ws" for i in range(start, start + 600)]
                assert writer.post("/kb/revise", json={"statements": statements, "method": "add"}).is_success
        assert len(json.loads(ws.recv(timeout=GENEROUS))) == 600
        error = json.loads(ws.recv(timeout=GENEROUS))
        assert (error["status"], error["code"], error["details"]) == (413, "too_many_rows", {"limit": 1000})
        with pytest.raises(ConnectionClosed) as closed:
            ws.recv(timeout=GENEROUS)
        assert closed.value.rcvd is not None and closed.value.rcvd.code == 1008
    until(lambda: live.services.hub.listener_count == 0)
