"""The load benchmark, short: 50 concurrent dialogues and the 30 Hz perception writer for a few
seconds against a real service; no request fails and the KB is consistent afterwards (the writer's
live facts exactly, and a closure equal to a fresh recomputation). Figures are not asserted here:
they are the benchmark's (`situated bench load`)."""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor

from bench.load import ADD, RETRACT, START, TURN, run


def test_fifty_dialogues_and_a_perception_writer_without_errors_and_a_consistent_kb() -> None:
    # In a thread of its own, as from the CLI: other tests (Playwright's sync API) may leave an
    # event loop running in this one.
    with ThreadPoolExecutor(1) as pool:
        report = pool.submit(run, 5.0, 50, 30.0).result()
    assert report.errors == 0, report.table()
    assert len(report.routes[START].latencies) == 50
    assert report.routes[TURN].latencies and report.routes[ADD].latencies and report.routes[RETRACT].latencies
    assert report.closure_equal and report.live_facts_ok, report.table()
    assert report.ok
