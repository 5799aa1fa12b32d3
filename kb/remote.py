"""``RemoteKB``: a read replica of a KB kept in a SPARQL 1.1 store (issue 9, scale-out).

Exactly one process writes: an in-process ``KB`` whose commits kb.mirror.SparqlMirror copies to
the store. Any number of processes read through ``RemoteKB``, which has the public API of ``KB``
and gives the same answers, each read answered by SPARQL requests (kb.remotequery,
kb.remotedescribe, kb.remotesparql)::

    kb = RemoteKB("sparql+http://127.0.0.1:7878?dataset=site1", writes=writer)
    kb["myself sees ?obj"]
    kb += "myself sees cup_1"      # checked here, committed by the writer

Writes are checked exactly as ``KB`` checks them and forwarded to ``writes`` (kb.writetarget);
the writer updates the store before acknowledging, so a read after a write sees it. Subscriptions
are evaluated by polling the store's revision (kb.remoteevents).

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
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from kb.arguments import Models_, compiled, model_names, optional_term, parse_term, render
from kb.deadline import Budget, Deadline
from kb.endpoint import SparqlEndpoint
from kb.errors import KbError
from kb.events import Callback, ErrorCallback, event_id
from kb.formats import export_format
from kb.query import Row, TooManyRows
from kb.rdfio import serialize
from kb.remotedescribe import StoreDescriber
from kb.remoteevents import ActiveListener, Poller
from kb.remotequery import Graphs, Meta, StoreQueries
from kb.remotesparql import answer, run
from kb.store import ALL_MODELS, DEFAULT_MODEL
from kb.sugar import KnowledgeCoreSugar
from kb.summary import Summary
from kb.terms import as_list, parse_ground
from kb.writetarget import ReplicaWrites, WriteTarget

__all__ = ["RemoteKB", "WriteTarget"]



class RemoteKB(KnowledgeCoreSugar):
    """The ``KB`` API over a dataset of a SPARQL store; reads are requests, writes go to ``writes``."""

    def __init__(self, store: str | SparqlEndpoint, writes: WriteTarget | None = None, *,
                 poll_interval: float = 0.1) -> None:
        """``store``: a ``sparql+http://`` URL (kb.endpoint) or an endpoint, which stays the
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

    def __enter__(self) -> RemoteKB:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

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

    def _one_model(self, models: Models_) -> Graphs:
        found = self._read_models(models)
        if len(found) != 1:
            raise KbError("this call takes exactly one model")
        return found[0]

    # --- queries --------------------------------------------------------------------------

    def find(self, patterns: str | Sequence[str], vars: Sequence[str] | None = None,
             models: Models_ = None, *, max_rows: int | None = None,
             timeout: float | None = None) -> list[Any]:
        """Rows of bindings for a conjunction of patterns; for ground patterns, the patterns
        themselves if they all hold, else ``[]`` (kb-compat §3.2). With ``max_rows``, a query
        with more rows raises ``kb.query.TooManyRows``; past ``timeout`` seconds,
        ``kb.deadline.QueryTimeout``. One request per model."""
        texts = tuple(as_list(patterns))
        if not texts:
            raise KbError("find needs at least one pattern")
        query = compiled(texts, vars)
        deadline = Deadline.after(timeout)
        targets = self._read_models(models)
        if query.ground:
            return list(texts) if any(self._queries.holds(query, g, deadline) for g in targets) else []
        found: set[Row] = set()
        limit = None if max_rows is None else max_rows + 1
        for graphs in targets:
            found |= self._queries.rows(query, graphs, limit, deadline)
            if max_rows is not None and len(found) > max_rows:
                raise TooManyRows(max_rows)
        return render(query, found)

    def exist(self, patterns: str | Sequence[str], models: Models_ = None) -> bool:
        texts = tuple(as_list(patterns))
        if not texts:
            raise KbError("exist needs at least one pattern")
        query = compiled(texts, None)
        return any(self._queries.holds(query, g) for g in self._read_models(models))

    def lookup(self, query: str, models: Models_ = None) -> list[list[str]]:
        """``[[name, type], ...]``: exact matches first, then approximate ones (§3.4)."""
        if not isinstance(query, str):
            raise KbError(f"lookup takes a string, got {query!r}")
        return self._describer.lookup(query, self._read_models(models))

    def about(self, term: str, models: Models_ = None) -> list[list[Any]]:
        node = optional_term(term)
        return self._describer.about(node, term, self._read_models(models))

    def details(self, term: str, models: Models_ = None, origin: bool = False) -> dict[str, Any]:
        """kb-compat §3.3; with ``origin``, also ``"asserted"``: one flag per relation, true when
        it is asserted in the model, false when it is only inferred."""
        node = parse_term(term)
        return self._describer.details(node, self._one_model(models), origin)

    def label(self, term: str, lang: str | None = None, models: Models_ = None) -> str:
        if lang is not None and not isinstance(lang, str):
            raise KbError(f"lang must be a language code such as 'en', got {lang!r}")
        node = parse_term(term)
        return self._describer.label(node, lang, self._one_model(models))

    def classesof(self, term: str, direct: bool = False, models: Models_ = None) -> list[str]:
        node = parse_term(term)
        return self._describer.classes_of(node, direct, self._read_models(models))

    def sparql(self, query: str, model: str | Sequence[str] | None = None, *,
               timeout: float | None = None, max_rows: int | None = None) -> dict[str, Any]:
        """Read-only SPARQL 1.1 on one model: W3C JSON results plus the ``query`` (§3.7).
        ``timeout`` and ``max_rows`` as for ``KB.sparql``; the store is asked for the whole
        answer, read until the deadline, and its rows are counted once read."""
        return answer(self._endpoint, query, self._one_model(model), Deadline.after(timeout), max_rows)

    def sparql_serialize(self, query: str, fmt: str, model: str | None = None, *,
                         timeout: float | None = None, max_rows: int | None = None) -> tuple[str, bytes]:
        """Run a read-only query and serialise its result (``json``, ``xml``, ``csv``, ``tsv``
        for SELECT/ASK; RDF formats for CONSTRUCT/DESCRIBE); returns (result type, bytes)."""
        result = run(self._endpoint, query, self._one_model(model), Deadline.after(timeout), max_rows)
        return result.type, result.serialize(format=fmt, encoding="utf-8") or b""

    # --- writes (checked here, made by the writer) ----------------------------------------

    def sparql_update(self, update: str, models: Models_ = None) -> None:
        """SPARQL INSERT DATA / DELETE DATA as ONE batch, made by the writer."""
        self._writes.sparql_update(update, models)
        self._events.sync()

    def update(self, stmts: str | Sequence[str], models: Models_ = None, lifespan: float = 0) -> None:
        """Add statements; a functional property's new value replaces the old one (§3.5)."""
        self._writes.update(stmts, models, lifespan)
        self._events.sync()

    add = update

    def remove(self, stmts: str | Sequence[str], models: Models_ = None) -> int:
        """Retract statements; statements with variables are one conjunction whose every match is
        retracted (K12). Facts that are only inferred stay (they are derived again). Returns the
        number of asserted triples the writer removed."""
        removed = self._writes.remove(stmts, models)
        self._events.sync()
        return removed

    retract = remove

    def apply(self, add: Sequence[str] = (), remove: Sequence[str] = (), models: Models_ = None,
              lifespan: float = 0) -> None:
        """Retract ``remove`` and assert ``add`` (ground statements) as ONE batch."""
        self._writes.apply(add, remove, models, lifespan)
        self._events.sync()

    def clear(self, keep_defaults: bool = True) -> None:
        """Drop every model's facts; the default ontology stays unless ``keep_defaults=False``."""
        self._writes.clear(keep_defaults)
        self._events.sync()

    def load(self, uri: str | Path, models: Models_ = None) -> None:
        """Add the triples of a local RDF file (read here, sent to the writer) as one batch."""
        self._writes.load(uri, models)
        self._events.sync()

    def load_data(self, data: str | bytes, fmt: str = "turtle", models: Models_ = None) -> None:
        """Add the triples of an RDF document given as text (turtle, xml, json-ld, nt, ...)."""
        self._writes.load_data(data, fmt, models)
        self._events.sync()

    def save(self, path: str | Path, basename: str = "kb", models: Models_ = None) -> list[str]:
        """Write each model's asserted triples as RDF/XML to ``path/basename-<model>.rdf``."""
        folder = Path(path)
        if not folder.is_dir():
            raise KbError(f"cannot save to {str(path)!r}: not a directory")
        written = []
        for graphs in self._read_models(models):
            target = folder / f"{basename}-{graphs.model}.rdf"
            target.write_bytes(serialize(self._queries.triples(graphs, inferred=False), "xml"))
            written.append(str(target))
        return written

    def export(self, fmt: str = "turtle", model: str | None = None, inferred: bool = False) -> bytes:
        """A model's asserted (or, with ``inferred``, materialised) triples in an RDF format."""
        fmt = export_format(fmt).name
        return serialize(self._queries.triples(self._one_model(model), inferred), fmt)

    # --- events ---------------------------------------------------------------------------

    def subscribe(self, patterns: str | Sequence[str], callback: Callback, one_shot: bool = False,
                  models: Models_ = None, *, timeout: float | None = None, max_rows: int | None = None,
                  on_error: ErrorCallback | None = None) -> str:
        """Call ``callback(rows)`` with the new rows after each change; returns ``evt_<md5>``.
        Callbacks run on the polling thread. ``timeout``, ``max_rows`` and ``on_error`` as for
        ``KB.subscribe``: the first evaluation past them raises, a later one ends the
        subscription (it no longer holds up the polling of the others)."""
        texts = as_list(patterns)
        if not texts:
            raise KbError("subscribe needs at least one pattern")
        if not callable(callback):
            raise KbError(f"subscribe needs a callable that takes the new rows, got {callback!r}")
        if on_error is not None and not callable(on_error):
            raise KbError(f"on_error must be a callable that takes the error, got {on_error!r}")
        budget = Budget(timeout, max_rows)
        query = compiled(tuple(texts), None)
        names = model_names(models) or [DEFAULT_MODEL]
        sub_id = event_id(texts, one_shot, names)
        meta = self._queries.meta()  # read before the baseline: a later commit is evaluated again
        self._known(names, meta)
        baseline = self._events.rows(query, names, meta.models, max_rows, Deadline.after(timeout))
        self._events.subscribe(sub_id, query, names, one_shot, callback, baseline, meta.revision, budget,
                               on_error)
        return sub_id

    def unsubscribe(self, sub_id: str) -> bool:
        return self._events.unsubscribe(sub_id)

    def settle(self, timeout: float = 30.0) -> None:
        """Return once the subscriptions were evaluated against the store as it is now (writes
        made through this replica do it themselves; commits of other processes are seen at the
        next poll otherwise)."""
        self._events.sync(timeout)

    def on_active_concept(self, callback: ActiveListener) -> None:
        """Call ``callback(concepts)`` when the set of active concepts changes (polled)."""
        self._events.on_active_concept(callback)

    # --- housekeeping ---------------------------------------------------------------------

    def size(self, model: str | None = None, inferred: bool = True) -> int:
        return self._queries.size(self._one_model(model), inferred)

    def is_asserted(self, stmt: str, model: str | None = None) -> bool:
        """True if the statement was asserted (not only inferred) in the model."""
        triple = parse_ground(stmt)
        return self._queries.is_asserted(triple, self._one_model(model))
