"""rdflib's SPARQL parser made safe (issue 26, item 1): concurrent first parses of a fresh process
leave it working, and a parse counts against the query's budget (a large VALUES block or a long
sum is stopped at the deadline; a text over the bound is refused), without holding the KB.

A fresh process is the point of the first test: pyparsing learns each parse action's arity on
its first calls, so the test runs in a new interpreter whose grammar has never been used.
Bounds on time are generous (the machine is shared).
"""

from __future__ import annotations

import gc
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

import pytest
from rdflib.plugins.sparql.parser import parseQuery

from kb import KB, sparqlparse
from kb.deadline import Deadline
from kb.errors import QueryTimeout, QueryTooLarge
from kb.sparql import MAX_QUERY_CHARS

ROOT = Path(__file__).parents[2]
GENEROUS = 30.0

FIRST_PARSES = r'''
import threading
from kb import KB
from kb.sparql import check_query, parse_update

kb = KB()
texts = ["SELECT ?s WHERE { ?s ?p ?o } LIMIT 3", "ASK { ?s a owl:Class }",
         "SELECT (COUNT(*) AS ?n) WHERE { ?s ?p ?o FILTER(REGEX(STR(?s), 'x')) }",
         "CONSTRUCT { ?s ?p ?o } WHERE { ?s ?p ?o } LIMIT 2", "DESCRIBE <http://x.org/a>",
         "SELECT ?x WHERE { VALUES ?x { 1 2 3 } OPTIONAL { ?x ?y ?z } } ORDER BY DESC(?x)",
         "SELECT ?x (SAMPLE(?y) AS ?z) WHERE { ?x ?p ?y } GROUP BY ?x HAVING (COUNT(?y) > 1)"]
errors = []
start = threading.Barrier(48)

def first(n):
    start.wait()
    try:
        if n % 8 == 7:
            parse_update("INSERT DATA { <http://x.org/a> <http://x.org/b> 1 }")
        else:
            kb.sparql(texts[n % len(texts)], timeout=60)
    except Exception as exc:
        errors.append(repr(exc))

threads = [threading.Thread(target=first, args=(n,)) for n in range(48)]
for t in threads: t.start()
for t in threads: t.join()
later = []
for text in texts:
    try:
        kb.sparql(text, timeout=60)
    except Exception as exc:
        later.append(repr(exc))
print("errors", len(errors), errors[:3])
print("later", len(later), later[:3])
'''


def test_concurrent_first_parses_of_a_fresh_process_leave_the_parser_working() -> None:
    for _ in range(3):  # the race is one of timing: three fresh processes
        done = subprocess.run([sys.executable, "-c", FIRST_PARSES], capture_output=True, text=True,
                              timeout=300, cwd=ROOT, check=False)
        assert done.returncode == 0, done.stderr[-3000:]
        assert "errors 0 []" in done.stdout and "later 0 []" in done.stdout, done.stdout


@pytest.fixture(scope="module")
def kb() -> KB:
    with KB() as k:
        yield k


SUM = "SELECT ?x WHERE { BIND(" + "1+" * 20_000 + "1 AS ?x) }"
VALUES = "SELECT ?x WHERE { VALUES ?x { " + "1 " * 40_000 + "} }"


@pytest.mark.parametrize("query", [SUM, VALUES], ids=["sum", "values"])
def test_a_parse_is_stopped_at_the_query_budget(kb: KB, query: str) -> None:
    assert len(query) <= MAX_QUERY_CHARS
    start = time.monotonic()
    with pytest.raises(QueryTimeout, match=r"time budget of 0\.5 s"):
        kb.sparql(query, timeout=0.5)
    assert time.monotonic() - start < GENEROUS / 3
    assert kb.sparql("ASK { ?s ?p ?o }", timeout=5)["boolean"] is True  # the parser still works


def test_a_query_over_the_text_bound_is_refused_before_parsing(kb: KB) -> None:
    query = "SELECT ?x WHERE { VALUES ?x { " + "<x> " * (MAX_QUERY_CHARS // 4) + "} }"
    start = time.monotonic()
    with pytest.raises(QueryTooLarge, match=f"has {len(query)} characters; the limit is {MAX_QUERY_CHARS}"):
        kb.sparql(query)
    assert time.monotonic() - start < 1.0


def test_a_slow_parse_holds_neither_the_kb_nor_a_writer(kb: KB) -> None:
    failed: list[BaseException] = []

    def slow() -> None:
        try:
            kb.sparql(SUM, timeout=3)
        except QueryTimeout as exc:
            failed.append(exc)

    thread = threading.Thread(target=slow)
    thread.start()
    time.sleep(0.3)  # the parse is under way
    start = time.monotonic()
    kb += "cup_9 isOn table_9"
    wrote = time.monotonic() - start
    thread.join()
    assert failed and wrote < 1.0, f"a write waited {wrote:.1f} s behind a query's parse"


def test_a_parse_past_its_deadline_is_stopped_in_its_own_code_not_in_a_gc_callback(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # The collector runs its callbacks (a profiler's, hypothesis's) and finalizers in whatever
    # frame allocated: stopped there, the error would be dropped, the tracing removed, and the
    # parse run on to its end.
    deadline = Deadline(60)

    def callback(phase: str, info: dict[str, Any]) -> None:
        if phase == "start":
            deadline._at = 0.0  # the budget runs out during a collection in the parse

    parsed: list[bool] = []

    def parser(text: str) -> Any:
        gc.collect()
        tree = parseQuery(text)
        parsed.append(True)
        return tree

    monkeypatch.setattr(sparqlparse, "_CHECK_EVERY", 1)  # the clock looked at on every call
    gc.callbacks.append(callback)
    try:
        with pytest.raises(QueryTimeout):
            sparqlparse.parse("SELECT ?x WHERE { VALUES ?x { " + "1 " * 2_000 + "} }", parser, deadline)
    finally:
        gc.callbacks.remove(callback)
    assert parsed == []  # stopped inside the parse, not after it
