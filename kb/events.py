"""Subscriptions: a pattern query re-run after each change, firing with the rows that are new.

The semantics are knowledge_core's (kb-compat §3.6) without its defects: the rows true at
subscription time are the baseline and do not fire; each later change fires exactly once per
new row (K9), whatever caused it (a write, functional replacement, lifespan expiry); one-shot
subscriptions are removed after the first evaluation that fires, not the first evaluation (K8).
"""

from __future__ import annotations

import hashlib
import json
import logging
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

from rdflib import Variable

from kb.models import Delta
from kb.query import Query, Row, match_triple

_log = logging.getLogger(__name__)
ALL = "all"
Callback = Callable[[list[Any]], None]
Evaluate = Callable[["Subscription"], set[Row]]
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
    ) -> None:
        existing = self._by_id.get(sub_id)
        if existing is not None:
            existing.callbacks.append(callback)
            return
        constant = [p for _, p, _ in query.patterns]
        predicates = None if any(isinstance(p, Variable) for p in constant) else frozenset(constant)
        self._by_id[sub_id] = Subscription(
            sub_id, query, tuple(models), one_shot, [callback], predicates, set(baseline)
        )

    def remove(self, sub_id: str) -> bool:
        return self._by_id.pop(sub_id, None) is not None

    def clear(self) -> None:
        self._by_id.clear()

    def rebaseline(self, run: Evaluate) -> None:
        """Take the current rows as every subscription's baseline (after a clear)."""
        for sub in self._by_id.values():
            sub.last = run(sub)

    def evaluate(
        self, deltas: Sequence[Delta], run: Evaluate, still: StillHolds, render: Render
    ) -> list[Firing]:
        """Re-evaluate the subscriptions a change may affect; return what fires.

        A one-pattern subscription is updated from the delta alone (its rows can only appear
        through added triples and disappear through removed ones), so a broad subscription such
        as the viewer's ``?s ?p ?o`` costs as much as the change, not as the whole KB.
        """
        firings: list[Firing] = []
        for sub in list(self._by_id.values()):
            relevant = [d for d in deltas if ALL in sub.models or d.model in sub.models]
            if sub.predicates is not None:
                relevant = [d for d in relevant if _touches(d, sub.predicates)]
            if not relevant:
                continue
            if len(sub.query.patterns) == 1:
                new = _incremental(sub, relevant, still)
            else:
                current = run(sub)
                new = current - sub.last
                sub.last = current
            if not new:
                continue
            firings.append(Firing(sub.id, tuple(sub.callbacks), render(sub.query, new)))
            if sub.one_shot:
                del self._by_id[sub.id]
        return firings


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
