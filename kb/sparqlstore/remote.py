"""``RemoteKB``: a read replica of a KB kept in a SPARQL 1.1 store (issue 9, scale-out).

Exactly one process writes: an in-process ``KB`` whose commits kb.sparqlstore.mirror.SparqlMirror copies to
the store. Any number of processes read through ``RemoteKB``, which has the public API of ``KB``
and gives the same answers, each read answered by SPARQL requests (kb.sparqlstore.query,
kb.sparqlstore.describe, kb.sparqlstore.sparql)::

    kb = RemoteKB("sparql+http://127.0.0.1:7878?dataset=site1", writes=writer)
    kb["myself sees ?obj"]
    kb += "myself sees cup_1"      # checked here, committed by the writer

Writes are checked exactly as ``KB`` checks them and forwarded to ``writes`` (kb.sparqlstore.writetarget);
the writer updates the store before acknowledging, so a read after a write sees it. Subscriptions
are evaluated by polling the store's revision (kb.sparqlstore.events).

Where a replica cannot be the in-process KB exactly:

- the store keeps typed literals in canonical form (``"4.50"^^xsd:decimal`` is ``4.5``): rendered
  values are the same, but the lexical text searched by ``lookup``/``about`` is the canonical one,
  and two literals differing only in form are one;
- blank nodes are skolem IRIs in the store: results give them back as blank nodes, but inside a
  ``sparql()`` query ``isBlank``, ``STR`` and ``ORDER BY`` see IRIs;
- ``models()`` lists ``default`` first, then the others by name (the store keeps no creation order);
- lifespans are expired by the writer's reaper thread, not at the moment of the read;
- a call that needs several requests (several models, ``lookup``) may straddle a commit, and
  ``lock`` only serialises this process's callers: it does not freeze the store.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator, Sequence
from typing import Any

from rdflib.query import Result

from kb.arguments import Models_, model_names, render
from kb.deadline import Budget, Deadline
from kb.errors import KbError, TooManyRows
from kb.events import Callback, ErrorCallback
from kb.facade import Facade
from kb.models import ALL_MODELS, DEFAULT_MODEL
from kb.query import Query, Row
from kb.sparqlstore.describe import StoreDescriber
from kb.sparqlstore.endpoint import SparqlEndpoint
from kb.sparqlstore.events import ActiveListener, Poller
from kb.sparqlstore.query import Graphs, Meta, StoreQueries
from kb.sparqlstore.sparql import run
from kb.sparqlstore.writetarget import ReplicaWrites, WriteTarget
from kb.summary import Summary
from kb.terms import Node, Triple

__all__ = ["RemoteKB", "WriteTarget"]


class RemoteKB(Facade[Graphs]):
    """The ``KB`` API over a dataset of a SPARQL store; reads are requests, writes go to ``writes``."""

    def __init__(self, store: str | SparqlEndpoint, writes: WriteTarget | None = None, *,
                 poll_interval: float = 0.1) -> None:
        """``store``: a ``sparql+http://`` URL (kb.sparqlstore.endpoint) or an endpoint, which stays the
        caller's to close; ``writes``: where writes go (none: a read-only replica);
        ``poll_interval``: seconds between two looks at the revision while subscriptions exist."""
        if (isinstance(poll_interval, bool) or not isinstance(poll_interval, int | float)
                or not poll_interval > 0):
            raise KbError(f"poll_interval must be a number of seconds > 0, got {poll_interval!r}")
        # The write target is checked before a connection pool exists that would need closing.
        name = (f"{store.spec.query_url} (dataset {store.layout.dataset})"
                if isinstance(store, SparqlEndpoint) else store)
        self._writes = ReplicaWrites(writes, name)
        self._own_endpoint = not isinstance(store, SparqlEndpoint)
        self._endpoint = store if isinstance(store, SparqlEndpoint) else SparqlEndpoint(store)
        self._queries = StoreQueries(self._endpoint)
        self._describer = StoreDescriber(self._endpoint)
        self._events = Poller(self._queries, float(poll_interval))
        self._lock = threading.RLock()

    def close(self) -> None:
        """Stop the polling thread (if one was started) and close the connection to the store."""
        self._events.close()
        if self._own_endpoint:
            self._endpoint.close()

    @property
    def endpoint(self) -> SparqlEndpoint:
        return self._endpoint

    @property
    def revision(self) -> int:
        """The writer's revision, as the store holds it (0 for an empty dataset)."""
        return self._queries.meta().revision or 0

    @property
    def lock(self) -> threading.RLock:
        """A lock of this process only, for callers that group several calls. It does NOT freeze
        the store: the writer may commit between two reads made under it."""
        return self._lock

    def summary(self) -> Summary:
        """Revision, sizes of the default model and model names, as the store holds them (one
        request each: they may straddle a commit)."""
        meta = self._queries.meta()
        return Summary(meta.revision or 0, self.size(), self.size(inferred=False), tuple(meta.models))

    # --- models ---------------------------------------------------------------------------

    def models(self) -> list[str]:
        return list(self._queries.meta().models)

    def _read_models(self, models: Models_) -> list[Graphs]:
        names = model_names(models)
        if all(name == DEFAULT_MODEL for name in names):  # always there: no need to ask
            return [self._queries.graphs(DEFAULT_MODEL) for _ in names or [DEFAULT_MODEL]]
        return self._known(names, self._queries.meta())

    def _known(self, names: list[str], meta: Meta) -> list[Graphs]:
        if ALL_MODELS in names:
            return [self._queries.graphs(n) for n in meta.models]
        for name in names:
            if name not in meta.models and name != DEFAULT_MODEL:
                raise KbError(f"unknown model {name!r}; known models: {', '.join(meta.models)}")
        return [self._queries.graphs(n) for n in names]

    # --- the primitives of kb.facade.Facade (arguments already checked) --------------

    def _find(self, texts: tuple[str, ...], query: Query, models: Models_, max_rows: int | None,
              deadline: Deadline | None) -> list[Any]:
        targets = self._read_models(models)
        if query.ground:
            return list(texts) if any(self._queries.holds(query, g, deadline) for g in targets) else []
        found: set[Row] = set()
        limit = None if max_rows is None else max_rows + 1
        for graphs in targets:  # one request per model
            found |= self._queries.rows(query, graphs, limit, deadline)
            if max_rows is not None and len(found) > max_rows:
                raise TooManyRows(max_rows)
        return render(query, found)

    def _exist(self, query: Query, models: Models_) -> bool:
        return any(self._queries.holds(query, g) for g in self._read_models(models))

    def _lookup(self, query: str, models: Models_) -> list[list[str]]:
        return self._describer.lookup(query, self._read_models(models))

    def _about(self, node: Node | None, raw: str, models: Models_) -> list[list[Any]]:
        return self._describer.about(node, raw, self._read_models(models))

    def _details(self, node: Node, models: Models_, origin: bool) -> dict[str, Any]:
        return self._describer.details(node, self._one_model(models), origin)

    def _label(self, node: Node, lang: str | None, models: Models_) -> str:
        return self._describer.label(node, lang, self._one_model(models))

    def _classes_of(self, node: Node, direct: bool, models: Models_) -> list[str]:
        return self._describer.classes_of(node, direct, self._read_models(models))

    def _sparql_result(self, query: str, model: Models_, deadline: Deadline | None,
                       max_rows: int | None) -> Result:
        # The store is asked for the whole answer, read until the deadline; rows counted once read.
        return run(self._endpoint, query, self._one_model(model), deadline, max_rows)

    def _triples(self, model: str | None, inferred: bool) -> list[Triple]:
        return list(self._queries.triples(self._one_model(model), inferred))

    def _asserted_by_model(self, models: Models_) -> Iterator[tuple[str, list[Triple]]]:
        for graphs in self._read_models(models):
            yield graphs.model, list(self._queries.triples(graphs, inferred=False))

    def _size(self, model: str | None, inferred: bool) -> int:
        return self._queries.size(self._one_model(model), inferred)

    def _is_asserted(self, triple: Triple, model: str | None) -> bool:
        return self._queries.is_asserted(triple, self._one_model(model))

    # Writes: checked by the facade, made by the writer (which updates the store before it
    # acknowledges, so a read after a write sees it); then the subscriptions are evaluated.

    def _writable(self) -> None:
        self._writes.require()

    def _update(self, texts: list[str], triples: list[Triple], models: Models_, lifespan: float) -> None:
        self._writes.require().update(texts, models, lifespan)
        self._events.sync()

    def _remove(self, texts: list[str], ground: list[Triple], patterns: Query | None,
                models: Models_) -> int:
        removed = self._writes.require().remove(texts, models)
        self._events.sync()
        return removed

    def _apply(self, add: tuple[list[str], list[Triple]], remove: tuple[list[str], list[Triple]],
               models: Models_, lifespan: float) -> None:
        self._writes.require().apply(add[0], remove[0], models, lifespan)
        self._events.sync()

    def _apply_models(self, texts: dict[str, tuple[list[str], list[str]]],
                      changes: dict[str, tuple[list[Triple], list[Triple]]], lifespan: float) -> None:
        self._writes.require().apply_models({name: {"add": add, "remove": remove}
                                             for name, (add, remove) in texts.items()}, lifespan)
        self._events.sync()

    def _clear(self, keep_defaults: bool) -> None:
        self._writes.require().clear(keep_defaults)
        self._events.sync()

    def _load(self, data: str | bytes, fmt: str, triples: Sequence[Triple], models: Models_) -> None:
        self._writes.require().load_data(data, fmt, models)
        self._events.sync()

    def _sparql_update(self, update: str, added: Sequence[Triple], removed: Sequence[Triple],
                       models: Models_) -> None:
        self._writes.require().sparql_update(update, models)
        self._events.sync()

    def _subscribe(self, sub_id: str, query: Query, names: list[str], one_shot: bool,
                   callback: Callback, budget: Budget, on_error: ErrorCallback | None) -> None:
        # Callbacks run on the polling thread; a bounded subscription no longer holds up the
        # polling of the others past its budget.
        meta = self._queries.meta()  # read before the baseline: a later commit is evaluated again
        self._known(names, meta)
        deadline = Deadline.after(budget.timeout)
        baseline = self._events.rows(query, names, meta.models, budget.max_rows, deadline)
        self._events.subscribe(sub_id, query, names, one_shot, callback, baseline, meta.revision, budget,
                               on_error)

    # --- events ---------------------------------------------------------------------------

    def unsubscribe(self, sub_id: str) -> bool:
        return self._events.unsubscribe(sub_id)

    def settle(self, timeout: float = 30.0) -> None:
        """Return once the subscriptions were evaluated against the store as it is now (writes
        made through this replica do it themselves; commits of other processes are seen at the
        next poll otherwise)."""
        self._events.sync(timeout)

    def on_active_concept(self, callback: ActiveListener) -> Callable[[], None]:
        """Call ``callback(concepts)`` when the set of active concepts changes (polled); returns
        what removes it."""
        return self._events.on_active_concept(callback)
