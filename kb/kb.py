"""``KB``: the knowledge_core-compatible facade (kb-compat §3).

Client code written for ``knowledge_core.api.KB`` runs against it unchanged:

>>> from kb import KB
>>> kb = KB()                       # the default ontology, no server
>>> kb += "myself sees cup_abcd"
>>> kb["myself sees ?obj"]
[{'obj': 'cup_abcd'}]
>>> kb.details("cup_abcd")["label"]["default"]
'cup_abcd'

Every method is thread-safe. Reads see the state between two commits, never half a batch.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Sequence
from contextlib import suppress
from pathlib import Path
from typing import Any

from rdflib.query import Result

from kb import describe
from kb.arguments import (
    Models_,
    matches,
    model_names,
    render,
)
from kb.batch import Batch
from kb.deadline import Budget, Deadline, holding, timed
from kb.errors import KbError, StorageError
from kb.events import Callback, ErrorCallback
from kb.facade import Facade
from kb.modelbounds import ModelBounds
from kb.models import ALL_MODELS, DEFAULT_MODEL, Model, Models
from kb.query import Query, holds, rows_in
from kb.rdfio import default_ontology, parse_location
from kb.reasonbudget import ReasoningBounds
from kb.sparql import check_query, execute
from kb.summary import Summary
from kb.tboxbudget import TBoxBounds
from kb.terms import Node, Triple, shorten
from kb.writer import ActiveListener, Commit, CommitListener, Writer

DEFAULT_MAX_MODELS_PER_WRITE = 16


class KB(Facade[Model]):
    """An in-process OWL/RDF knowledge base with incremental OWL RL reasoning."""

    def __init__(self, ontology: bool | Sequence[str | Path] = True, *,
                 clock: Callable[[], float] = time.time,
                 max_models_per_write: int = DEFAULT_MAX_MODELS_PER_WRITE,
                 max_models: int | None = None, max_model_statements: int | None = None,
                 tbox_bounds: TBoxBounds | None = None,
                 reasoning_bounds: ReasoningBounds | None = None) -> None:
        """``ontology``: True for the default ORO-compatible ontology, False for none, or files.
        ``max_models_per_write``: the most models one write may name (each new model starts with
        a copy of the ontology's closure, so one write naming thousands would take minutes and
        gigabytes under the KB lock). ``max_models``: the most models the KB holds (``default``
        included), ``max_model_statements``: the most statements of its own a model other than
        ``default`` holds; None: no bound (kb.modelbounds; a write past one is ``ModelLimit``).
        ``tbox_bounds``: what one write's TBox change may cost the reasoner (``kb.tboxbudget``;
        the defaults when None), ``reasoning_bounds`` what its facts may (``kb.reasonbudget``)."""
        bounds = ModelBounds(max_models, max_model_statements)
        if isinstance(max_models_per_write, bool) or not isinstance(max_models_per_write, int) \
                or max_models_per_write < 1:
            raise KbError(f"max_models_per_write must be a positive integer, got {max_models_per_write!r}")
        self._max_models_per_write = max_models_per_write
        if ontology is True:
            defaults: tuple[Triple, ...] = default_ontology()
        elif ontology is False:
            defaults = ()
        else:
            defaults = tuple(t for path in ontology for t in parse_location(str(path)))
        self._lock = threading.RLock()
        self._models = Models(defaults)
        self._writer = Writer(self._lock, self._models, render, clock, bounds, tbox_bounds, reasoning_bounds)
        self._clock = clock

    def close(self) -> None:
        """Stop the expiry thread (if one was started)."""
        self._writer.close()

    @property
    def revision(self) -> int:
        """Increases by one with every committed change."""
        return self._writer.revision

    @property
    def lock(self) -> threading.RLock:
        """Held by every read and write; hold it to read several answers from one state."""
        return self._lock

    def summary(self) -> Summary:
        """Revision, sizes of the default model and model names after the last change, without
        waiting for the KB lock (``/health`` answers while a long query runs)."""
        return self._writer.summary

    # --- models ---------------------------------------------------------------------------

    def models(self) -> list[str]:
        with self._lock:
            return self._models.names

    def _read_models(self, models: Models_) -> list[Model]:
        names = model_names(models)
        if not names:
            return [self._models.default]
        if ALL_MODELS in names:
            return [m for n in self._models.names if (m := self._models.get(n)) is not None]
        found = []
        for name in names:
            model = self._models.get(name)
            if model is None:
                raise KbError(f"unknown model {name!r}; known models: {', '.join(self._models.names)}")
            found.append(model)
        return found

    def _write_models(self, models: Models_) -> list[str]:
        names = model_names(models)
        if len(names) > self._max_models_per_write:
            raise KbError(f"{len(names)} models in one write; the limit is {self._max_models_per_write} "
                          "(KB's max_models_per_write)")
        if not names:
            return [DEFAULT_MODEL]
        if ALL_MODELS in names:
            return self._models.names
        return names

    # --- the primitives of kb.facade.Facade (arguments already checked) --------------

    def _find(self, texts: tuple[str, ...], query: Query, models: Models_, max_rows: int | None,
              deadline: Deadline | None) -> list[Any]:
        self._expire_due()
        with holding(self._lock, deadline):
            targets = self._read_models(models)
            indexes = [timed(m.closure, deadline) for m in targets]
            if query.ground:
                return list(texts) if any(holds(index, query) for index in indexes) else []
            return render(query, rows_in(indexes, query, max_rows), self._models.shorts)

    def _exist(self, query: Query, models: Models_) -> bool:
        self._expire_due()
        with self._lock:
            return any(holds(m.closure, query) for m in self._read_models(models))

    def _lookup(self, query: str, models: Models_) -> list[list[str]]:
        self._expire_due()
        with self._lock:
            found = [(m, *describe.lookup(m.closure, query)) for m in self._read_models(models)]
            return [[str(shorten(t)), describe.term_kind(m.closure, t)] for t, m in describe.merged(found)]

    def _about(self, node: Node | None, raw: str, models: Models_) -> list[list[Any]]:
        self._expire_due()
        with self._lock:
            found: list[list[Any]] = []
            for model in self._read_models(models):
                found.extend(st for st in describe.about(model.closure, node, raw) if st not in found)
            return found

    def _details(self, node: Node, models: Models_, origin: bool) -> dict[str, Any]:
        self._expire_due()
        with self._lock:
            model = self._one_model(models)
            return describe.details(model.closure, model.asserted, node, origin)

    def _label(self, node: Node, lang: str | None, models: Models_) -> str:
        with self._lock:
            return describe.label(self._one_model(models).closure, node, lang)

    def _classes_of(self, node: Node, direct: bool, models: Models_) -> list[str]:
        self._expire_due()
        with self._lock:
            found: set[str] = set()
            for model in self._read_models(models):
                found.update(describe.classes_of(model.closure, model.asserted, node, direct))
            return sorted(found)

    def _all_classes(self, direct: bool, model: str | None) -> dict[str, list[str]]:
        self._expire_due()
        with self._lock:
            target = self._one_model(model)
            return describe.all_classes(target.closure, target.asserted, direct)

    def _all_labels(self, lang: str | None, model: str | None) -> dict[str, str]:
        with self._lock:
            return describe.all_labels(self._one_model(model).closure, lang)

    def _sparql_result(self, query: str, model: Models_, deadline: Deadline | None,
                       max_rows: int | None) -> Result:
        checked = check_query(query, deadline)  # parsed before taking the KB: no write waits on it
        with holding(self._lock, deadline):
            return execute(self._one_model(model).closure, checked, deadline, max_rows)

    def _triples(self, model: str | None, inferred: bool) -> list[Triple]:
        with self._lock:
            target = self._one_model(model)
            return list(target.closure if inferred else target.asserted)

    def _asserted_by_model(self, models: Models_) -> list[tuple[str, list[Triple]]]:
        with self._lock:
            return [(m.name, list(m.asserted)) for m in self._read_models(models)]

    def _size(self, model: str | None, inferred: bool) -> int:
        with self._lock:
            target = self._one_model(model)
            return len(target.closure if inferred else target.asserted)

    def _is_asserted(self, triple: Triple, model: str | None) -> bool:
        with self._lock:
            return self._one_model(model).is_asserted(triple)

    def _update(self, texts: list[str], triples: list[Triple], models: Models_, lifespan: float) -> None:
        self._writer.commit(Batch(self._write_models(models), add=triples, lifespan=lifespan))

    def _remove(self, texts: list[str], ground: list[Triple], patterns: Query | None,
                models: Models_) -> int:
        names = self._write_models(models)
        batch = Batch(names, remove=ground, replace_functional=False)
        if patterns is None:
            return _asserted_removed(self._writer.commit(batch))
        with self._lock:  # the matches and their retraction see one state
            for model in self._read_models(names):
                batch.remove_by_model[model.name] = matches(model, patterns.patterns)
            return _asserted_removed(self._writer.commit(batch))

    def _apply(self, add: tuple[list[str], list[Triple]], remove: tuple[list[str], list[Triple]],
               models: Models_, lifespan: float) -> None:
        batch = Batch(self._write_models(models), add=add[1], remove=remove[1], lifespan=lifespan)
        self._writer.commit(batch)

    def _apply_models(self, texts: dict[str, tuple[list[str], list[str]]],
                      changes: dict[str, tuple[list[Triple], list[Triple]]], lifespan: float) -> None:
        batch = Batch(self._write_models(list(changes)), lifespan=lifespan,
                      add_by_model={name: add for name, (add, _) in changes.items()},
                      remove_by_model={name: remove for name, (_, remove) in changes.items()})
        self._writer.commit(batch)

    def _clear(self, keep_defaults: bool) -> None:
        self._writer.clear(keep_defaults)

    def _load(self, data: str | bytes, fmt: str, triples: Sequence[Triple], models: Models_) -> None:
        self._writer.commit(Batch(self._write_models(models), add=list(triples), replace_functional=False))

    def _sparql_update(self, update: str, added: Sequence[Triple], removed: Sequence[Triple],
                       models: Models_) -> None:
        self._writer.commit(Batch(self._write_models(models), add=list(added), remove=list(removed),
                                  replace_functional=False))

    def _subscribe(self, sub_id: str, query: Query, names: list[str], one_shot: bool,
                   callback: Callback, budget: Budget, on_error: ErrorCallback | None) -> None:
        deadline = Deadline.after(budget.timeout)
        with holding(self._lock, deadline):
            started = time.monotonic()
            indexes = [timed(m.closure, deadline) for m in self._read_models(names)]
            baseline = rows_in(indexes, query, budget.max_rows)
            self._writer.subscriptions.add(sub_id, query, names, one_shot, callback, baseline, budget,
                                           on_error, cost=time.monotonic() - started)

    # --- events and the write path ----------------------------------------------------------

    def unsubscribe(self, sub_id: str) -> bool:
        with self._lock:
            return self._writer.subscriptions.remove(sub_id)

    def on_active_concept(self, callback: ActiveListener) -> Callable[[], None]:
        """Call ``callback`` with the sorted active concepts whenever they change (kb-compat
        §3.7); returns what removes it."""
        with self._lock:
            return self._writer.on_active_concept(callback)

    def on_commit(self, listener: CommitListener, durable: bool = False) -> Callable[[], None]:
        """Called under the lock with every commit (for journals and mirrors); a ``durable``
        listener may refuse the commit by raising, which undoes it (see ``Writer.on_commit``)."""
        return self._writer.on_commit(listener, durable)

    @property
    def writer(self) -> Writer:
        """The write path (state snapshots and replay for the journal)."""
        return self._writer

    def expire(self, now: float | None = None) -> Commit | None:
        """Retract the statements whose lifespan is over now (the expiry thread calls this)."""
        return self._writer.expire(now)

    def _expire_due(self) -> None:
        due = self._writer.expiries.next_due()
        if due is not None and due <= self._clock():
            # A read still answers on a full disk: the statements stay until their retraction
            # is durable; the expiry thread retries it and reports the failure in /health.
            with suppress(StorageError):
                self._writer.expire()


def _asserted_removed(commit: Commit | None) -> int:
    return 0 if commit is None else sum(len(delta.asserted_removed) for delta in commit.deltas)
