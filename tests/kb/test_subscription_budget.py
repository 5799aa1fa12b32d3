"""Bounded subscriptions (issue 19, item 8): a subscription's first evaluation past its budget is
refused and nothing is subscribed; a later evaluation past it ends the subscription with the
error, told to the subscriber; however many such subscriptions there are, a commit is held back
about one budget, not one per subscription, and the other subscriptions go on.

Bounds on time are generous (the machine is shared): they tell "about one budget" from "one
budget per subscription" or "minutes", never measure speed.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from typing import Any

import pytest

from kb import KB, KbError
from kb.arguments import compiled, parse_term, render
from kb.deadline import Budget, Deadline
from kb.errors import QueryTimeout, TooManyRows
from kb.events import Subscription, Subscriptions
from kb.models import Delta
from kb.query import Row
from tests.kb.test_summary import lock_held_elsewhere

GENEROUS = 30.0
THINGS = [f"thing_{i} isOn table_{i % 7}" for i in range(1500)]


SLOW_FEW_ROWS = ["* ?p *", "* ?q *", "* * *"]  # pairs of predicates: few rows after n³ steps
CAP = 10_000  # rows, as the service caps them: the time budget is what stops these


def cartesian(trigger: str, var: str = "?z") -> list[str]:
    """No row (nor any work) until ``<trigger> isOn ...`` holds; then n³ steps."""
    return [f"{trigger} isOn {var}", *SLOW_FEW_ROWS]


@pytest.fixture(scope="module")
def kb() -> Iterator[KB]:
    with KB() as k:
        k += THINGS
        yield k


class Subscriber:
    def __init__(self) -> None:
        self.rows: list[list[Any]] = []
        self.errors: list[KbError] = []

    def __call__(self, rows: list[Any]) -> None:
        self.rows.append(rows)

    def error(self, error: KbError) -> None:
        self.errors.append(error)


def test_a_first_evaluation_past_the_budget_subscribes_nothing(kb: KB) -> None:
    subscriptions = len(kb.writer.subscriptions)
    start = time.monotonic()
    with pytest.raises(QueryTimeout, match=r"time budget of 0\.5 s"):
        kb.subscribe(SLOW_FEW_ROWS, Subscriber(), timeout=0.5, max_rows=CAP)
    assert time.monotonic() - start < GENEROUS
    with pytest.raises(TooManyRows, match="more than 100 rows"):
        kb.subscribe(["?a isOn ?t"], Subscriber(), max_rows=100, timeout=GENEROUS)
    with lock_held_elsewhere(kb), pytest.raises(QueryTimeout, match="waited for the KB"):
        kb.subscribe(["?a isOn table_1"], Subscriber(), timeout=0.3)
    assert len(kb.writer.subscriptions) == subscriptions
    with pytest.raises(KbError, match="positive number of seconds"):
        kb.subscribe(["?a isOn ?t"], Subscriber(), timeout=0)
    with pytest.raises(KbError, match="max_rows must be a positive integer"):
        kb.subscribe(["?a isOn ?t"], Subscriber(), max_rows=0)


def test_a_subscription_within_its_budget_works_as_before(kb: KB) -> None:
    sub = Subscriber()
    sub_id = kb.subscribe(["?x isOn shelf_1", "?x isOn ?t"], sub, timeout=GENEROUS, max_rows=100, on_error=sub.error)
    kb.add(["thing_3 isOn shelf_1"])
    assert sorted(r["t"] for r in sub.rows[0]) == ["shelf_1", "table_3"] and not sub.errors
    assert kb.unsubscribe(sub_id)


def test_a_live_subscription_past_its_budget_is_ended_and_commits_go_on() -> None:
    with KB() as kb:
        kb += THINGS
        budget = 0.5
        hostile = [Subscriber() for _ in range(10)]
        for n, sub in enumerate(hostile):
            kb.subscribe(cartesian("trigger", f"?z{n}"), sub, timeout=budget, max_rows=CAP, on_error=sub.error)
        cheap, own = Subscriber(), Subscriber()
        kb.subscribe(["trigger isOn ?s", "?s rdf:type ?k"], cheap, timeout=budget, on_error=cheap.error)
        kb.subscribe(["trigger isOn ?s", "?s isOn ?w"], own)  # no budget: the process's own
        def ended() -> int:
            return sum(1 for sub in hostile if sub.errors)

        # One shared budget per commit: each over-budget evaluation spends all of it, so a commit
        # ends at most one hostile subscription and defers the rest (one budget per subscription
        # would hold it ten budgets; unbounded, for ever). Counted, not timed: a busy machine
        # slows every evaluation but does not change how many fit in one budget.
        kb.add(["trigger isOn shelf_1", "shelf_1 isOn floor_1", "shelf_1 rdf:type Shelf"])
        assert ended() <= 1
        assert own.rows == [[{"s": "shelf_1", "w": "floor_1"}]]
        for n in range(len(hostile) + 1):
            before = ended()
            kb.add([f"noise_{n} isOn floor_1"])
            assert ended() - before <= 1
        for sub in hostile:
            assert sub.rows == [] and len(sub.errors) == 1
            assert isinstance(sub.errors[0], QueryTimeout) and "time budget of 0.5 s" in str(sub.errors[0])
        assert len(kb.writer.subscriptions) == 2  # ended: no commit evaluates them any more
        assert not cheap.errors and {r["k"] for r in cheap.rows[0]} >= {"Shelf"} and len(cheap.rows) == 1


def test_a_clear_ends_a_subscription_its_budget_cannot_evaluate() -> None:
    with KB() as kb:
        kb.remove(["Human rdfs:comment ?c"])  # a fact of the ontology: clear() brings it back
        hostile = Subscriber()
        kb.subscribe(["Human rdfs:comment ?c", *SLOW_FEW_ROWS], hostile, timeout=0.5, max_rows=CAP,
                     on_error=hostile.error)
        start = time.monotonic()
        kb.clear()
        assert time.monotonic() - start < GENEROUS
        assert len(hostile.errors) == 1 and isinstance(hostile.errors[0], QueryTimeout)
        assert len(kb.writer.subscriptions) == 0


def test_a_live_subscription_past_its_row_cap_is_ended() -> None:
    with KB() as kb:
        one, join = Subscriber(), Subscriber()
        kb.subscribe(["?x isOn ?t"], one, max_rows=10, on_error=one.error)
        kb.subscribe(["?x isOn ?t", "?t rdf:type Table"], join, max_rows=10, on_error=join.error)
        kb.add(["table_1 rdf:type Table"] + [f"thing_{i} isOn table_1" for i in range(5)])
        assert len(one.rows) == len(join.rows) == 1 and not one.errors and not join.errors
        kb.add([f"thing_{i} isOn table_1" for i in range(5, 20)])
        for sub in (one, join):
            assert len(sub.rows) == 1 and len(sub.errors) == 1
            assert isinstance(sub.errors[0], TooManyRows) and "more than 10 rows" in str(sub.errors[0])
        assert len(kb.writer.subscriptions) == 0


def test_an_ending_reaches_every_callback_of_a_shared_subscription_and_is_logged(
        caplog: pytest.LogCaptureFixture) -> None:
    with KB() as kb:
        first, second = Subscriber(), Subscriber()
        ids = {kb.subscribe(["?x isOn ?t"], sub, max_rows=2, on_error=sub.error) for sub in (first, second)}
        kb.subscribe(["?x isOn ?t"], Subscriber(), max_rows=2)  # no on_error: the log says it
        kb.add([f"thing_{i} isOn table_1" for i in range(3)])
        assert len(ids) == 1 and len(first.errors) == len(second.errors) == 1
        assert f"subscription {ids.pop()} ended: the query has more than 2 rows" in caplog.text


def test_subscribing_and_committing_from_many_threads_stays_consistent() -> None:
    with KB() as kb:
        kb += THINGS[:50]
        subs = [Subscriber() for _ in range(8)]
        done = threading.Barrier(len(subs) + 1)

        def subscribe(n: int) -> None:
            kb.subscribe([f"?x isOn shelf_{n}", "?x isOn ?t"], subs[n], timeout=GENEROUS, max_rows=1000,
                         on_error=subs[n].error)
            done.wait(GENEROUS)

        threads = [threading.Thread(target=subscribe, args=(n,)) for n in range(len(subs))]
        for thread in threads:
            thread.start()
        done.wait(GENEROUS)
        for thread in threads:
            thread.join()
        kb.add([f"thing_{n} isOn shelf_{n}" for n in range(len(subs))])
        assert all(len(sub.rows) == 1 and not sub.errors for sub in subs)


# --- the policy of one commit's budget (kb.events.Subscriptions), with evaluations made to order ---

ISON = parse_term("isOn")
TRIGGER = (parse_term("trigger"), ISON, parse_term("shelf_1"))


def _budgeted(subs: Subscriptions, sub_id: str, seconds: float, cost: float) -> Subscriber:
    sub = Subscriber()
    subs.add(sub_id, compiled(("trigger isOn ?s", f"?s isOn ?{sub_id}"), None), ["default"], False, sub,
             set(), Budget(seconds), sub.error, cost=cost)
    return sub


def _commit(subs: Subscriptions, slow: set[str], takes: dict[str, float] | None = None) -> list[Any]:
    """Evaluate after a change that touches every subscription: those named in ``slow`` never
    finish (they stop at their deadline), those in ``takes`` answer after so many seconds (or
    stop at their deadline), the others answer one row at once."""
    def run(sub: Subscription, deadline: Deadline | None) -> set[Row]:
        done = time.monotonic() + (takes or {}).get(sub.id, 0.0)
        while sub.id in slow or time.monotonic() < done:
            assert deadline is not None
            deadline.check()
            time.sleep(0.005)
        return {(parse_term("shelf_1"), parse_term(f"{sub.id}_place"))}

    deliveries = subs.evaluate([Delta("default", added=[TRIGGER])], run, lambda sub, row: True, render)
    for delivery in deliveries:
        delivery.deliver()
    return deliveries


def test_a_commit_gives_the_bounded_subscriptions_one_budget_and_defers_the_rest() -> None:
    subs = Subscriptions()
    budget = 0.5
    hostile = _budgeted(subs, "hostile", budget, cost=0.0)  # looked cheapest: evaluated first
    late = [_budgeted(subs, f"late{n}", budget, cost=0.1) for n in range(3)]
    start = time.monotonic()
    _commit(subs, slow={"hostile"})
    assert time.monotonic() - start < 3 * budget  # three more budgets if each had its own
    assert len(hostile.errors) == 1 and isinstance(hostile.errors[0], QueryTimeout)
    assert all(sub.rows == [] and not sub.errors for sub in late)  # not evaluated, not ended
    assert "hostile" not in subs and all(f"late{n}" in subs for n in range(3))
    _commit(subs, slow=set())  # the next commit evaluates them first
    assert all(len(sub.rows) == 1 and not sub.errors for sub in late)


def test_a_subscription_stopped_by_others_spending_the_budget_is_deferred_then_ended() -> None:
    subs = Subscriptions()
    budget = 0.6
    first = _budgeted(subs, "first", budget, cost=0.0)
    second = _budgeted(subs, "second", budget, cost=0.1)
    _commit(subs, slow={"second"}, takes={"first": budget / 2})
    # first answered within the commit's budget; second ran in what was left, was stopped by the
    # commit's deadline before its own, and waits for the next commit...
    assert len(first.rows) == 1 and second.errors == [] and "second" in subs
    _commit(subs, slow={"second"})
    # ... where it goes first, with its whole budget: past it, it is ended.
    assert len(second.errors) == 1 and "second" not in subs and second.rows == []
    assert not first.errors and "first" in subs
