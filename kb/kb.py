"""``KB``: the knowledge_core-compatible facade (kb-compat §3).

Client code written for ``knowledge_core.api.KB`` runs against it unchanged::

    from kb import KB
    kb = KB()                       # the default ontology, no server
    kb += "myself sees cup_abcd"
    kb["myself sees ?obj"]          # [{"obj": "cup_abcd"}]
    kb.details("cup_abcd")["label"]["default"]

Every method is thread-safe. Reads see the state between two commits, never half a batch.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Sequence
from contextlib import suppress
from pathlib import Path
from typing import Any

from rdflib import Variable

from kb import describe
from kb.arguments import (
    Models_,
    compiled,
    lifespan_seconds,
    matches,
    model_names,
    optional_term,
    parse_term,
    render,
)
from kb.deadline import Budget, Deadline, holding, timed
from kb.errors import KbError, StorageError
from kb.events import Callback, ErrorCallback, event_id
from kb.formats import export_format
from kb.query import holds, rows_in
from kb.rdfio import default_ontology, parse_data, parse_location, serialize
from kb.sparql import execute, parse_update, to_json
from kb.store import ALL_MODELS, DEFAULT_MODEL, Model, Models
from kb.sugar import KnowledgeCoreSugar
from kb.summary import Summary
from kb.terms import Node, Triple, as_list, parse_ground, parse_patterns, shorten
from kb.writer import ActiveListener, Batch, Commit, CommitListener, Writer

DEFAULT_MAX_MODELS_PER_WRITE = 16


class KB(KnowledgeCoreSugar):
    """An in-process OWL/RDF knowledge base with incremental OWL RL reasoning."""

    def __init__(self, ontology: bool | Sequence[str | Path] = True, *,
                 clock: Callable[[], float] = time.time,
                 max_models_per_write: int = DEFAULT_MAX_MODELS_PER_WRITE) -> None:
        """``ontology``: True for the default ORO-compatible ontology, False for none, or files.
        ``max_models_per_write``: the most models one write may name (each new model starts with
        a copy of the ontology's closure, so one write naming thousands would take minutes and
        gigabytes under the KB lock)."""
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
        self._writer = Writer(self._lock, self._models, render, clock)
        self._clock = clock

    def close(self) -> None:
        """Stop the expiry thread (if one was started)."""
        self._writer.close()

    def __enter__(self) -> KB:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

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

    def _one_model(self, models: Models_) -> Model:
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
        with more rows raises ``kb.query.TooManyRows`` as soon as it finds one too many; with
        ``timeout`` (seconds, waiting for the KB included), ``kb.deadline.QueryTimeout``."""
        texts = tuple(as_list(patterns))
        if not texts:
            raise KbError("find needs at least one pattern")
        query = compiled(texts, vars)
        deadline = Deadline.after(timeout)
        self._expire_due()
        with holding(self._lock, deadline):
            targets = self._read_models(models)
            indexes = [timed(m.closure, deadline) for m in targets]
            if query.ground:
                return list(texts) if any(holds(index, query) for index in indexes) else []
            return render(query, rows_in(indexes, query, max_rows))

    def exist(self, patterns: str | Sequence[str], models: Models_ = None) -> bool:
        texts = tuple(as_list(patterns))
        if not texts:
            raise KbError("exist needs at least one pattern")
        query = compiled(texts, None)
        self._expire_due()
        with self._lock:
            return any(holds(m.closure, query) for m in self._read_models(models))

    def lookup(self, query: str, models: Models_ = None) -> list[list[str]]:
        """``[[name, type], ...]``: exact matches first, then approximate ones (§3.4)."""
        if not isinstance(query, str):
            raise KbError(f"lookup takes a string, got {query!r}")
        self._expire_due()
        with self._lock:
            exact: dict[Node, str] = {}
            approx: dict[Node, str] = {}
            for model in self._read_models(models):
                e, a = describe.lookup(model.closure, query)
                for t in e:
                    exact.setdefault(t, describe.term_kind(model.closure, t))
                for t in a:
                    approx.setdefault(t, describe.term_kind(model.closure, t))
            for t in exact:
                approx.pop(t, None)
            key = describe._sort_key
            return [[str(shorten(t)), exact[t]] for t in sorted(exact, key=key)] + [
                [str(shorten(t)), approx[t]] for t in sorted(approx, key=key)
            ]

    def about(self, term: str, models: Models_ = None) -> list[list[Any]]:
        node = optional_term(term)
        self._expire_due()
        with self._lock:
            found: list[list[Any]] = []
            for model in self._read_models(models):
                found.extend(st for st in describe.about(model.closure, node, term) if st not in found)
            return found

    def details(self, term: str, models: Models_ = None, origin: bool = False) -> dict[str, Any]:
        """kb-compat §3.3; with ``origin``, also ``"asserted"``: one flag per relation, true when
        it is asserted in the model, false when it is only inferred."""
        node = parse_term(term)
        self._expire_due()
        with self._lock:
            model = self._one_model(models)
            return describe.details(model.closure, model.asserted, node, origin)

    def label(self, term: str, lang: str | None = None, models: Models_ = None) -> str:
        if lang is not None and not isinstance(lang, str):
            raise KbError(f"lang must be a language code such as 'en', got {lang!r}")
        node = parse_term(term)
        with self._lock:
            return describe.label(self._one_model(models).closure, node, lang)

    def classesof(self, term: str, direct: bool = False, models: Models_ = None) -> list[str]:
        node = parse_term(term)
        self._expire_due()
        with self._lock:
            found: set[str] = set()
            for model in self._read_models(models):
                found.update(describe.classes_of(model.closure, model.asserted, node, direct))
            return sorted(found)

    def sparql(self, query: str, model: str | Sequence[str] | None = None, *,
               timeout: float | None = None, max_rows: int | None = None) -> dict[str, Any]:
        """Read-only SPARQL 1.1 on one model: W3C JSON results plus the ``query`` (§3.7).
        ``timeout`` (seconds, waiting for the KB included) stops it with
        ``kb.deadline.QueryTimeout``; more than ``max_rows`` rows (or triples of a graph) is
        ``kb.query.TooManyRows``."""
        deadline = Deadline.after(timeout)
        with holding(self._lock, deadline):
            result = execute(self._one_model(model).closure, query, deadline, max_rows)
        return to_json(result, query)  # the result no longer reads the KB: no lock needed

    def sparql_serialize(self, query: str, fmt: str, model: str | None = None, *,
                         timeout: float | None = None, max_rows: int | None = None) -> tuple[str, bytes]:
        """Run a read-only query and serialise its result (``json``, ``xml``, ``csv``, ``tsv``
        for SELECT/ASK; RDF formats for CONSTRUCT/DESCRIBE); returns (result type, bytes).
        ``timeout`` and ``max_rows`` as for ``sparql``."""
        deadline = Deadline.after(timeout)
        with holding(self._lock, deadline):
            result = execute(self._one_model(model).closure, query, deadline, max_rows)
        return result.type, result.serialize(format=fmt, encoding="utf-8") or b""

    def sparql_update(self, update: str, models: Models_ = None) -> None:
        """Apply SPARQL INSERT DATA / DELETE DATA as ONE batch (no functional replacement);
        other update forms are refused (``kb.sparql.UnsupportedUpdate``) before any change."""
        added, removed = parse_update(update)
        self._writer.commit(Batch(self._write_models(models), add=added, remove=removed,
                                  replace_functional=False))

    # --- writes ---------------------------------------------------------------------------

    def update(self, stmts: str | Sequence[str], models: Models_ = None, lifespan: float = 0) -> None:
        """Add statements; a functional property's new value replaces the old one (§3.5)."""
        triples = [parse_ground(s) for s in as_list(stmts)]
        batch = Batch(self._write_models(models), add=triples, lifespan=lifespan_seconds(lifespan))
        self._writer.commit(batch)

    add = update

    def remove(self, stmts: str | Sequence[str], models: Models_ = None) -> int:
        """Retract statements; statements with variables are one conjunction whose every
        match is retracted (K12). Facts that are only inferred stay (they are derived again).
        Returns the number of asserted triples removed, over all the models written."""
        ground: list[Triple] = []
        patterns: list[str] = []
        for text in as_list(stmts):
            pattern = parse_patterns([text])[0]
            if any(isinstance(t, Variable) for t in pattern):
                patterns.append(text)
            else:
                ground.append(pattern)  # type: ignore[arg-type]  # no variables in it
        names = self._write_models(models)
        batch = Batch(names, remove=ground, replace_functional=False)
        if patterns:
            query = compiled(tuple(patterns), None)
            with self._lock:
                for model in self._read_models(names):
                    batch.remove_by_model[model.name] = matches(model, query.patterns)
                return _asserted_removed(self._writer.commit(batch))
        return _asserted_removed(self._writer.commit(batch))

    retract = remove

    def apply(self, add: Sequence[str] = (), remove: Sequence[str] = (), models: Models_ = None,
              lifespan: float = 0) -> None:
        """Retract ``remove`` and assert ``add`` (ground statements) as ONE batch: one revision,
        one reasoning pass, one event evaluation. A perception tick or a scene diff uses this."""
        added = [parse_ground(s) for s in as_list(add)]
        removed = [parse_ground(s) for s in as_list(remove)]
        self._writer.commit(
            Batch(self._write_models(models), add=added, remove=removed, lifespan=lifespan_seconds(lifespan))
        )

    def clear(self, keep_defaults: bool = True) -> None:
        """Drop every model's facts; the default ontology stays unless ``keep_defaults=False``
        (K5). Subscriptions stay and see the facts disappear."""
        self._writer.clear(keep_defaults)

    def load(self, uri: str | Path, models: Models_ = None) -> None:
        """Add the triples of a local RDF file (any rdflib format) as one batch."""
        if not isinstance(uri, str | Path):
            raise KbError(f"load takes a file path or file:// URI, got {uri!r}")
        self._load(parse_location(str(uri)), models)

    def load_data(self, data: str | bytes, fmt: str = "turtle", models: Models_ = None) -> None:
        """Add the triples of an RDF document given as text (turtle, xml, json-ld, nt, ...)."""
        self._load(parse_data(data, fmt), models)

    def _load(self, triples: Sequence[Triple], models: Models_) -> None:
        self._writer.commit(Batch(self._write_models(models), add=list(triples), replace_functional=False))

    def save(self, path: str | Path, basename: str = "kb", models: Models_ = None) -> list[str]:
        """Write each model's asserted triples as RDF/XML to ``path/basename-<model>.rdf``."""
        folder = Path(path)
        if not folder.is_dir():
            raise KbError(f"cannot save to {str(path)!r}: not a directory")
        written = []
        with self._lock:
            for model in self._read_models(models):
                target = folder / f"{basename}-{model.name}.rdf"
                target.write_bytes(serialize(model.asserted, "xml"))
                written.append(str(target))
        return written

    def export(self, fmt: str = "turtle", model: str | None = None, inferred: bool = False) -> bytes:
        """A model's asserted (or, with ``inferred``, materialised) triples in an RDF format."""
        fmt = export_format(fmt).name
        with self._lock:
            target = self._one_model(model)
            triples = list(target.closure if inferred else target.asserted)
        return serialize(triples, fmt)

    # --- events ---------------------------------------------------------------------------

    def subscribe(self, patterns: str | Sequence[str], callback: Callback, one_shot: bool = False,
                  models: Models_ = None, *, timeout: float | None = None, max_rows: int | None = None,
                  on_error: ErrorCallback | None = None) -> str:
        """Call ``callback(rows)`` with the new rows after each change; returns ``evt_<md5>``.
        With ``timeout`` (seconds) or ``max_rows``, every evaluation is bounded: the first one
        (waiting for the KB included) raises ``QueryTimeout`` or ``TooManyRows`` and nothing is
        subscribed; a later one past them ends the subscription and calls ``on_error(error)``
        (kb.events)."""
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
        deadline = Deadline.after(timeout)
        with holding(self._lock, deadline):
            started = time.monotonic()
            indexes = [timed(m.closure, deadline) for m in self._read_models(names)]
            baseline = rows_in(indexes, query, max_rows)
            self._writer.subscriptions.add(sub_id, query, names, one_shot, callback, baseline, budget,
                                           on_error, cost=time.monotonic() - started)
        return sub_id

    def unsubscribe(self, sub_id: str) -> bool:
        with self._lock:
            return self._writer.subscriptions.remove(sub_id)

    def on_active_concept(self, callback: ActiveListener) -> None:
        self._writer.on_active_concept(callback)

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

    # --- housekeeping ---------------------------------------------------------------------

    def size(self, model: str | None = None, inferred: bool = True) -> int:
        with self._lock:
            target = self._one_model(model)
            return len(target.closure if inferred else target.asserted)

    def is_asserted(self, stmt: str, model: str | None = None) -> bool:
        """True if the statement was asserted (not only inferred) in the model."""
        triple = parse_ground(stmt)
        with self._lock:
            return self._one_model(model).is_asserted(triple)


def _asserted_removed(commit: Commit | None) -> int:
    return 0 if commit is None else sum(len(delta.asserted_removed) for delta in commit.deltas)
