"""The single write path: batches, functional replacement, lifespans and events.

Every change to the KB goes through ``Writer.commit`` under the KB lock: the batch is applied to
each target model, the revision moves on once, subscriptions are evaluated against the result,
and callbacks run after the lock is released. Lifespan expiry is just another commit, so it
re-reasons and fires events exactly like an explicit retract (K9).
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

from rdflib.namespace import OWL, RDF

from kb.batch import ACTIVE_CONCEPT, Batch, last_functional_wins
from kb.deadline import Deadline, timed
from kb.errors import KbError, ReasoningTooLarge
from kb.events import Delivery, Firing, Subscriptions
from kb.gcpause import paused
from kb.lifespan import Expiries
from kb.modelbounds import ModelBounds
from kb.models import ALL_MODELS, Delta, Model, Models, ModelsState
from kb.query import Query, Row, holds_row, rows_in
from kb.reaper import Reaper
from kb.reasonbudget import ReasoningBounds, StepBudget
from kb.summary import Summary, summarise
from kb.tboxbudget import TBoxBounds
from kb.terms import Triple, shorten

log = logging.getLogger(__name__)

Render = Callable[[Query, set[Row]], list[dict[str, Any]]]


@dataclass(frozen=True)
class Commit:
    """One committed change, as journal and listeners see it."""

    revision: int
    deltas: tuple[Delta, ...]
    expiries: tuple[tuple[str, Triple, float], ...]
    # Set by clear(): None for an ordinary change, else the keep_defaults flag.
    cleared: bool | None = None


@dataclass(frozen=True)
class State:
    """The asserted state of every model as differences from the default ontology, for snapshots."""

    revision: int
    extra: dict[str, list[Triple]]
    missing: dict[str, list[Triple]]
    expiries: list[tuple[str, Triple, float]]


CommitListener = Callable[[Commit], None]
Gate = Callable[[], None]
ActiveListener = Callable[[list[str]], None]


class Writer:
    """Applies batches to models; owns lifespans, subscriptions and the revision counter."""

    def __init__(self, lock: threading.RLock, models: Models, render: Render,
                 clock: Callable[[], float] = time.time, bounds: ModelBounds | None = None,
                 tbox_bounds: TBoxBounds | None = None,
                 reasoning_bounds: ReasoningBounds | None = None) -> None:
        self.lock = lock
        self.models = models
        self.bounds = bounds or ModelBounds()
        self.tbox_bounds = tbox_bounds if tbox_bounds is not None else TBoxBounds()
        self.reasoning_bounds = reasoning_bounds if reasoning_bounds is not None else ReasoningBounds()
        self.subscriptions = Subscriptions()
        self.expiries = Expiries()
        self.revision = 0
        self._render = render
        self._clock = clock
        self._commit_listeners: list[CommitListener] = []  # the durable ones first
        self._gates: list[Gate] = []
        self._durable_count = 0
        self._active_listeners: list[ActiveListener] = []
        self.reaper = Reaper(lock, self.expiries, self.expire, clock)
        self.expiry_status = self.reaper.status  # for /health
        self.summary: Summary = summarise(0, models)  # replaced at each change; read without the lock

    # --- listeners -----------------------------------------------------------------------

    def on_commit(self, listener: CommitListener, durable: bool = False) -> Callable[[], None]:
        """Register a listener; returns the function that unregisters it. A ``durable`` listener
        (journal, store mirror) may refuse a commit by raising; durable listeners are called
        before the others, so a refused commit reaches no observer and consumes no revision."""
        with self.lock:
            if durable:
                self._durable_count += 1
                self._commit_listeners.insert(self._durable_count - 1, listener)
            else:
                self._commit_listeners.append(listener)

        def remove() -> None:
            with self.lock:
                if listener in self._commit_listeners:
                    if self._commit_listeners.index(listener) < self._durable_count:
                        self._durable_count -= 1
                    self._commit_listeners.remove(listener)

        return remove

    def gate(self, check: Gate) -> Callable[[], None]:
        """Register a check every commit (and clear) passes before anything changes, under the
        lock; returns the function that unregisters it. A check that raises refuses the write
        whole: nothing is applied, no listener is called and no revision is consumed (a store
        mirror that knows its store is out of reach refuses this way, so that refused writes do not
        move the revision its reconciliation waits on)."""
        with self.lock:
            self._gates.append(check)

        def remove() -> None:
            with self.lock:
                if check in self._gates:
                    self._gates.remove(check)

        return remove

    def _pass_gates(self) -> None:
        for check in self._gates:
            check()

    def on_active_concept(self, listener: ActiveListener) -> Callable[[], None]:
        """Call ``listener`` with the sorted active concepts whenever they change; returns what
        removes it."""
        self._active_listeners.append(listener)

        def remove() -> None:
            with self.lock:
                if listener in self._active_listeners:
                    self._active_listeners.remove(listener)

        return remove

    # --- committing ----------------------------------------------------------------------

    def commit(self, batch: Batch) -> Commit | None:
        """Apply a batch to its models atomically; return the commit, or None if nothing changed."""
        with self.lock, paused(batch.size):
            try:
                firings, commit = self._commit_locked(batch)
            finally:
                self._summarise()
        for firing in firings:
            firing.deliver()
        return commit

    def _commit_locked(self, batch: Batch) -> tuple[list[Delivery], Commit | None]:
        self._pass_gates()
        now = self._clock()
        deltas: list[Delta] = []
        expiries: list[tuple[str, Triple, float]] = []
        active_before = self._active_concepts()
        functional = self.functional_properties() if batch.replace_functional else frozenset()
        self.bounds.check(self.models, batch)  # before anything changes: refused means nothing did
        undo = _Undo(new_models=[n for n in batch.models if self.models.get(n) is None])
        changes: list[tuple[str, Model, list[Triple], list[Triple]]] = []
        for name in batch.models:
            model = self.models.create(name)
            remove = list(batch.remove) + batch.remove_by_model.get(name, [])
            add = last_functional_wins([*batch.add, *batch.add_by_model.get(name, ())], functional)
            for s, p, o in add:
                if p in functional:
                    remove.extend((s, p, old) for old in model.asserted.objects(s, p) if old != o)
            changes.append((name, model, add, remove))
        try:  # every model's TBox change within the bounds, before any model changes
            tboxes = [model.plan_tbox(add, remove, self.tbox_bounds) for _n, model, add, remove in changes]
        except KbError:
            for name in undo.new_models:
                self.models.drop(name)
            raise
        budget = StepBudget(self.reasoning_bounds.allowance(batch.size))
        applied: list[Delta] = []
        try:
            for (name, model, add, remove), tbox in zip(changes, tboxes, strict=True):
                self.expiries.remember(name, (*add, *remove), undo.expiries)
                delta = model.apply(add, remove, tbox, budget)
                applied.append(delta)
                if len(self.expiries):
                    for t in delta.asserted_removed:
                        self.expiries.discard(name, t)
                self.expiries.stamp(name, add, batch.lifespan_of, now, undo.expiries, expiries)
                if delta or expiries:
                    deltas.append(delta)
        except ReasoningTooLarge:  # the model that ran out is as it was; the others are put back
            self._revert(applied, undo)
            raise
        if not deltas:
            return [], None
        self.revision += 1
        commit = Commit(self.revision, tuple(deltas), tuple(expiries))
        self._publish(commit, undo)
        self.models.prune_terms()
        if expiries:
            self.reaper.wake()
        firings = self._evaluate(deltas)
        active_after = self._active_concepts()
        if active_after != active_before:
            concepts = sorted(active_after)
            firings.append(Firing("active_concepts", tuple(self._active_listeners), concepts))
        return firings, commit

    def _publish(self, commit: Commit, undo: _Undo) -> None:
        """Hand the commit to the listeners (store mirror, journal). If one refuses it (the store
        is unreachable, the disk is full), the batch is undone in memory and the error raised:
        nothing of it stays. Listeners that already took it get the undoing commit."""
        accepted: list[CommitListener] = []
        try:
            for listener in self._commit_listeners:
                listener(commit)
                accepted.append(listener)
        except (KbError, OSError):
            self._undo(commit, undo, accepted)
            raise

    def _undo(self, commit: Commit, undo: _Undo, accepted: list[CommitListener]) -> None:
        deltas, restored = self._revert(commit.deltas, undo)
        if not accepted:
            self.revision -= 1  # nobody saw the refused revision
            return
        self.revision += 1
        undoing = Commit(self.revision, tuple(deltas), tuple(restored))
        for listener in accepted:
            try:
                listener(undoing)
            except (KbError, OSError):
                log.exception("a commit listener could not take the undoing of a refused commit")

    def _revert(self, applied: Iterable[Delta],
                undo: _Undo) -> tuple[list[Delta], list[tuple[str, Triple, float]]]:
        """Put back what a batch changed in memory; return the undoing deltas and expiries."""
        deltas = []
        for delta in applied:
            model = self.models.get(delta.model)
            if model is not None:
                deltas.append(model.apply(delta.asserted_removed, delta.asserted_added))
        restored: list[tuple[str, Triple, float]] = []
        for (name, triple), at in undo.expiries.items():
            if at is None:
                self.expiries.discard(name, triple)
            else:
                self.expiries.set(name, triple, at)
            restored.append((name, triple, at or 0.0))
        for name in undo.new_models:
            self.models.drop(name)
        return deltas, restored

    def _evaluate(self, deltas: Iterable[Delta]) -> list[Delivery]:
        changed = [d for d in deltas if d.added or d.removed]
        if not changed or not len(self.subscriptions):
            return []
        return self.subscriptions.evaluate(changed, self.current_rows, self.still_holds, self._render)

    def still_holds(self, sub: Any, row: Row) -> bool:
        names = self.models.names if ALL_MODELS in sub.models else sub.models
        pattern = sub.query.patterns[0]
        return any(
            holds_row(model.closure, pattern, sub.query.projection, row)
            for name in names
            if (model := self.models.get(name)) is not None
        )

    def current_rows(self, sub: Any, deadline: Deadline | None = None) -> set[Row]:
        """The subscription's rows now; past the deadline ``QueryTimeout``, past its row cap
        ``TooManyRows``."""
        names = self.models.names if ALL_MODELS in sub.models else sub.models
        models = [model for name in names if (model := self.models.get(name)) is not None]
        return rows_in((timed(model.closure, deadline) for model in models), sub.query, sub.budget.max_rows)

    def functional_properties(self) -> frozenset[Any]:
        """Declared and inferred functional properties of the default model (kb-compat §3.5)."""
        return frozenset(self.models.default.closure.subjects(RDF.type, OWL.FunctionalProperty))

    def _active_concepts(self) -> frozenset[str]:
        if not self._active_listeners:
            return frozenset()
        subjects = self.models.default.closure.subjects(RDF.type, ACTIVE_CONCEPT)
        return frozenset(str(shorten(s)) for s in subjects)

    def clear(self, keep_defaults: bool) -> None:
        """Drop every model's facts. If a listener refuses (the disk is full, the store is down),
        the models and lifespans are put back and the error raised: nothing changed."""
        with self.lock:
            self._pass_gates()
            saved, expiries = self.models.reset(keep_defaults), self.expiries.items()
            self.expiries.clear()
            self.revision += 1
            commit = Commit(self.revision, (), (), cleared=keep_defaults)
            accepted: list[CommitListener] = []
            try:
                for listener in self._commit_listeners:
                    listener(commit)
                    accepted.append(listener)
            except (KbError, OSError):
                self._undo_clear(saved, expiries, accepted)
                raise
            finally:
                self._summarise()
            endings = self.subscriptions.rebaseline(self.current_rows)
        for ending in endings:
            ending.deliver()

    def _undo_clear(self, saved: ModelsState, expiries: list[tuple[str, Triple, float]],
                    accepted: list[CommitListener]) -> None:
        cleared = {name: set(m.asserted) for name in self.models.names if (m := self.models.get(name))}
        self.models.restore(saved)
        for name, triple, at in expiries:
            self.expiries.set(name, triple, at)
        if not accepted:
            self.revision -= 1  # nobody saw the refused revision
            return
        # Listeners that took the clear get the state back as one commit; a model the clear
        # removed counts as the default ontology, as a model a commit creates does.
        defaults = set(self.models.defaults)
        deltas = []
        for name in self.models.names:
            model = self.models.get(name)
            if model is not None:
                before, after = cleared.get(name, defaults), set(model.asserted)
                deltas.append(Delta(name, asserted_added=sorted(after - before, key=str),
                                    asserted_removed=sorted(before - after, key=str)))
        self.revision += 1
        undoing = Commit(self.revision, tuple(deltas), tuple(expiries))
        for listener in accepted:
            try:
                listener(undoing)
            except (KbError, OSError):
                log.exception("a commit listener could not take the undoing of a refused clear")

    def _summarise(self) -> None:
        self.summary = summarise(self.revision, self.models)

    def state(self) -> State:
        with self.lock:
            defaults = set(self.models.defaults)
            extra: dict[str, list[Triple]] = {}
            missing: dict[str, list[Triple]] = {}
            for name in self.models.names:
                model = self.models.get(name)
                if model is None:
                    continue
                asserted = set(model.asserted)
                extra[name] = sorted(asserted - defaults, key=str)
                missing[name] = sorted(defaults - asserted, key=str)
            return State(self.revision, extra, missing, self.expiries.items())

    def restore(self, model: str, add: list[Triple], remove: list[Triple],
                expiries: list[tuple[Triple, float]], revision: int | None = None) -> None:
        """Replay recorded asserted changes as they were (no functional replacement, explicit
        expiry times); used by journal recovery before the service starts."""
        with self.lock, paused(len(add) + len(remove)):
            target = self.models.create(model)
            target.apply(add, remove)
            for triple in remove:
                self.expiries.discard(model, triple)
            for triple, at in expiries:
                if at > 0:
                    self.expiries.set(model, triple, at)
                else:
                    self.expiries.discard(model, triple)
            if any(at > 0 for _triple, at in expiries):
                self.reaper.wake()
            self.revision = revision if revision is not None else self.revision + 1
            self._summarise()

    # --- lifespans -----------------------------------------------------------------------

    def expire(self, now: float | None = None) -> Commit | None:
        """Retract every statement whose lifespan is over, as one commit per call."""
        with self.lock:
            at = self._clock() if now is None else now
            due = self.expiries.pop_due(at)
            if not due:
                return None
            by_model: dict[str, list[Triple]] = {}
            for model, triple in due:
                by_model.setdefault(model, []).append(triple)
            batch = Batch(models=list(by_model), remove_by_model=by_model, replace_functional=False)
            try:
                firings, commit = self._commit_locked(batch)
            except (KbError, OSError):
                for model, triple in due:  # still due: the next attempt retracts them
                    self.expiries.set(model, triple, at)
                raise
            finally:
                self._summarise()
        for firing in firings:
            firing.deliver()
        return commit

    def close(self) -> None:
        self.reaper.close()


@dataclass
class _Undo:
    """What undoing a batch needs besides its deltas: the models it created, earlier expiries."""

    new_models: list[str]
    expiries: dict[tuple[str, Triple], float | None] = field(default_factory=dict)
