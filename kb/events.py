"""Subscriptions: a pattern query re-run after each change, firing with the rows that are new.

The semantics are knowledge_core's (kb-compat §3.6) without its defects: the rows true at
subscription time are the baseline and do not fire; each later change fires exactly once per
new row (K9), whatever caused it (a write, functional replacement, lifespan expiry); one-shot
subscriptions are removed after the first evaluation that fires, not the first evaluation (K8).

A subscription may have a ``Budget`` (the service gives every subscriber its query limits): its
every evaluation then stops past the time budget or the row cap, and the subscription is ended
with the error, delivered to its ``on_error`` callbacks. A commit evaluates bounded subscriptions
after the others, cheapest (as last measured) first, under one shared deadline of one budget
(``SharedBudget``): however many there are, they hold a commit back about one budget. Those the
commit had no time left for are not ended but evaluated first at the next commit, against the
rows they had (so their new rows fire late, and a row that came and went in between is missed;
after a clear, they keep their rows from before it until then).
"""

from __future__ import annotations

import hashlib
import json
import logging
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

from rdflib import Variable

from kb.deadline import UNBOUNDED, Budget, Deadline
from kb.errors import KbError, QueryTimeout, TooManyRows
from kb.models import Delta
from kb.query import Query, Row, match_triple

_log = logging.getLogger(__name__)
ALL = "all"
Callback = Callable[[list[Any]], None]
ErrorCallback = Callable[[KbError], None]
Evaluate = Callable[["Subscription", Deadline | None], set[Row]]
Render = Callable[[Query, set[Row]], list[dict[str, Any]]]
StillHolds = Callable[["Subscription", Row], bool]


def event_id(patterns: Sequence[str], one_shot: bool, models: Sequence[str]) -> str:
    """knowledge_core's id: md5 of the sorted patterns, the one-shot flag and the sorted models."""
    key = json.dumps([sorted(patterns), one_shot, sorted(models)])
    return "evt_" + hashlib.md5(key.encode(), usedforsecurity=False).hexdigest()


@dataclass(eq=False)
class Subscription:
    id: str
    query: Query
    models: tuple[str, ...]
    one_shot: bool
    callbacks: list[Callback]
    predicates: frozenset[Any] | None  # None: some pattern has a variable predicate
    last: set[Row] = field(default_factory=set)
    budget: Budget = UNBOUNDED
    on_error: list[ErrorCallback] = field(default_factory=list)
    cost: float = 0.0  # seconds its last full evaluation took
    pending: bool = False  # a commit's budget ran out before its evaluation: due at the next one
    spent: float = 0.0  # seconds of evaluations stopped by commits' budgets since its last answer

    def attach(self, callback: Callback, on_error: ErrorCallback | None) -> None:
        """Add a subscriber; one already there (an equal callable: the same function, or the same
        bound method) is not added again, so it is called once per trigger (knowledge_core)."""
        if callback not in self.callbacks:
            self.callbacks.append(callback)
        if on_error is not None and on_error not in self.on_error:
            self.on_error.append(on_error)

    def check_rows(self, rows: set[Row]) -> None:
        limit = self.budget.max_rows
        if limit is not None and len(rows) > limit:
            raise TooManyRows(limit)


@dataclass(frozen=True)
class Firing:
    """Rows to deliver to callbacks, produced under the KB lock and delivered after it."""

    subscription_id: str
    callbacks: tuple[Callback, ...]
    rows: list[Any]

    def deliver(self) -> None:
        for callback in self.callbacks:
            try:
                callback(self.rows)
            except Exception:  # noqa: BLE001 - subscriber code is arbitrary; the batch already committed
                # One broken subscriber must neither cost the others their rows nor turn a committed
                # write (or the expiry thread) into an error.
                _log.exception("subscriber %s raised on %d rows", self.subscription_id, len(self.rows))


@dataclass(frozen=True)
class Ending:
    """A subscription ended because an evaluation went past its budget: told to its subscribers
    after the KB lock is released, as a firing is."""

    subscription_id: str
    callbacks: tuple[ErrorCallback, ...]
    error: KbError

    def deliver(self) -> None:
        _log.warning("subscription %s ended: %s", self.subscription_id, self.error)
        for callback in self.callbacks:
            try:
                callback(self.error)
            except Exception:  # noqa: BLE001 - subscriber code is arbitrary, as for a firing
                _log.exception("subscriber %s raised on the end of its subscription", self.subscription_id)


Delivery = Firing | Ending


class Subscriptions:
    """The active subscriptions of one KB."""

    def __init__(self) -> None:
        self._by_id: dict[str, Subscription] = {}

    def __len__(self) -> int:
        return len(self._by_id)

    def __contains__(self, sub_id: str) -> bool:
        return sub_id in self._by_id

    def add(
        self,
        sub_id: str,
        query: Query,
        models: Sequence[str],
        one_shot: bool,
        callback: Callback,
        baseline: set[Row],
        budget: Budget = UNBOUNDED,
        on_error: ErrorCallback | None = None,
        cost: float = 0.0,
    ) -> None:
        existing = self._by_id.get(sub_id)
        if existing is None:
            constant = [p for _, p, _ in query.patterns]
            predicates = None if any(isinstance(p, Variable) for p in constant) else frozenset(constant)
            existing = self._by_id[sub_id] = Subscription(
                sub_id, query, tuple(models), one_shot, [], predicates, set(baseline), budget, cost=cost)
        existing.attach(callback, on_error)

    def remove(self, sub_id: str) -> bool:
        return self._by_id.pop(sub_id, None) is not None

    def clear(self) -> None:
        self._by_id.clear()

    def rebaseline(self, run: Evaluate) -> list[Delivery]:
        """Take the current rows as every subscription's baseline (after a clear); returns the
        endings of those that went past their budget."""
        endings: list[Delivery] = []
        commit = SharedBudget()
        for sub in self._in_order():
            try:
                current = commit.run(sub, run)
            except (QueryTimeout, TooManyRows) as exc:
                endings.append(self._end(sub, exc))
                continue
            if current is not None:
                sub.last = current
        return endings

    def evaluate(
        self, deltas: Sequence[Delta], run: Evaluate, still: StillHolds, render: Render
    ) -> list[Delivery]:
        """Re-evaluate the subscriptions a change may affect; return what fires and what ends.

        A one-pattern subscription is updated from the delta alone (its rows can only appear
        through added triples and disappear through removed ones), so a broad subscription such
        as the viewer's ``?s ?p ?o`` costs as much as the change, not as the whole KB.
        """
        firings: list[Delivery] = []
        commit = SharedBudget()
        for sub in self._in_order():
            relevant = [d for d in deltas if ALL in sub.models or d.model in sub.models]
            if sub.predicates is not None:
                relevant = [d for d in relevant if _touches(d, sub.predicates)]
            if not relevant and not sub.pending:
                continue
            try:
                if len(sub.query.patterns) == 1 and not sub.pending:
                    new = _incremental(sub, relevant, still)
                    sub.check_rows(sub.last)
                else:
                    current = commit.run(sub, run)
                    if current is None:
                        continue
                    new = current - sub.last
                    sub.last = current
            except (QueryTimeout, TooManyRows) as exc:
                firings.append(self._end(sub, exc))
                continue
            if not new:
                continue
            firings.append(Firing(sub.id, tuple(sub.callbacks), render(sub.query, new)))
            if sub.one_shot:
                del self._by_id[sub.id]
        return firings

    def _in_order(self) -> list[Subscription]:
        return in_cost_order(self._by_id.values())

    def _end(self, sub: Subscription, error: KbError) -> Ending:
        del self._by_id[sub.id]
        return Ending(sub.id, tuple(sub.on_error), error)


class SharedBudget:
    """One commit's (or poll's) full evaluations of bounded subscriptions, under one shared
    deadline: that of the first one evaluated. Each stops at the earlier of its own budget and
    the shared one. One stopped by the shared deadline (others spent the commit's budget) is left
    for the next commit, first in line; it is ended once its stopped evaluations add up to its
    own budget, as one stopped by its own budget is at once."""

    def __init__(self) -> None:
        self._shared: Deadline | None = None

    def run(self, sub: Subscription, run: Evaluate) -> set[Row] | None:
        """The rows now, or None when the commit's budget is spent (``sub`` is then pending)."""
        if self._shared is not None and not self._shared.remaining():
            sub.pending = True
            return None
        own = Deadline.after(sub.budget.timeout)
        if self._shared is None:
            self._shared = own
        deadline = self._shared if own is None else own.earlier(self._shared)
        started = time.monotonic()
        try:
            current = run(sub, deadline)
        except QueryTimeout:
            took = time.monotonic() - started
            sub.cost, sub.spent = max(sub.cost, took), sub.spent + took
            if own is not None and (not own.remaining() or sub.spent >= own.seconds):
                raise
            sub.pending = True
            return None
        sub.cost, sub.spent, sub.pending = time.monotonic() - started, 0.0, False
        sub.check_rows(current)
        return current


def in_cost_order(subs: Iterable[Subscription]) -> list[Subscription]:
    """Unbounded subscriptions (the process's own) first, then the bounded ones: those a
    commit's budget left for later first, then the cheapest (as last measured) first."""
    return sorted(subs, key=_cost_order)


def _cost_order(sub: Subscription) -> tuple[bool, bool, float]:
    bounded = sub.budget.bounded
    return bounded, bounded and not sub.pending, sub.cost if bounded else 0.0


def _touches(delta: Delta, predicates: frozenset[Any]) -> bool:
    return any(t[1] in predicates for t in delta.added) or any(t[1] in predicates for t in delta.removed)


def _incremental(sub: Subscription, deltas: Sequence[Delta], still: StillHolds) -> set[Row]:
    pattern, projection = sub.query.patterns[0], sub.query.projection
    new: set[Row] = set()
    for delta in deltas:
        for triple in delta.removed:
            row = match_triple(pattern, projection, triple)
            if row is not None and row in sub.last and not still(sub, row):
                sub.last.discard(row)
        for triple in delta.added:
            row = match_triple(pattern, projection, triple)
            if row is not None and row not in sub.last:
                sub.last.add(row)
                new.add(row)
    return new
