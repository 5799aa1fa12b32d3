"""The knowledge_core API, checked once: the base class of both KB backends.

Every public call parses and checks its arguments here, so the in-process ``kb.KB`` and the store
replica ``kb.sparqlstore.remote.RemoteKB`` refuse bad input with the same ``KbError`` and the same
message, before anything is read or written. A backend implements only the primitives (the
abstract ``_``-methods): reads over already-parsed queries and terms, and writes of already-parsed
statements (a replica forwards the original text to the writer, which is why both are passed).
"""

from __future__ import annotations

import threading
from abc import ABC, abstractmethod
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any, Generic, Self, TypeVar

from rdflib import RDF, RDFS, Variable
from rdflib.query import Result

from kb import describe
from kb.arguments import (
    Changes,
    Models_,
    compiled,
    lifespan_seconds,
    model_changes,
    model_names,
    optional_term,
    parse_term,
)
from kb.deadline import Budget, Deadline
from kb.errors import KbError
from kb.events import Callback, ErrorCallback, event_id
from kb.formats import export_format
from kb.gcpause import paused
from kb.index import TripleIndex
from kb.models import DEFAULT_MODEL
from kb.query import Query
from kb.rdfio import parse_data, read_location, serialize
from kb.sparql import parse_update, to_json
from kb.sparql import serialize as serialize_result
from kb.sugar import KnowledgeCoreSugar
from kb.summary import Summary
from kb.terms import Node, Triple, as_list, parse_ground, parse_patterns

#: What a backend reads one model through (``kb.models.Model``, or a replica's named graphs).
M = TypeVar("M")


class Facade(KnowledgeCoreSugar, ABC, Generic[M]):
    """The API of kb-compat §3 with its argument checks; subclasses answer the primitives."""

    @property
    @abstractmethod
    def revision(self) -> int:
        """Increases by one with every committed change."""

    @property
    @abstractmethod
    def lock(self) -> threading.RLock:
        """Held by every read and write of this process; hold it to group several calls."""

    @abstractmethod
    def summary(self) -> Summary:
        """Revision, sizes of the default model and model names, for ``/health``."""

    @abstractmethod
    def models(self) -> list[str]:
        """The names of the models (knowledge_core's "minds"), ``default`` among them."""

    @abstractmethod
    def close(self) -> None:
        """Release what the KB holds (threads, connections)."""

    def __enter__(self) -> Self:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # --- reads ----------------------------------------------------------------------------

    def find(self, patterns: str | Sequence[str], vars: Sequence[str] | None = None,
             models: Models_ = None, *, max_rows: int | None = None,
             timeout: float | None = None) -> list[Any]:
        """Rows of bindings for a conjunction of patterns; for ground patterns, the patterns
        themselves if they all hold, else ``[]`` (kb-compat §3.2). With ``max_rows``, a query
        with more rows raises ``kb.errors.TooManyRows`` as soon as it finds one too many; with
        ``timeout`` (seconds, waiting for the KB included), ``kb.errors.QueryTimeout``."""
        texts = tuple(as_list(patterns))
        if not texts:
            raise KbError("find needs at least one pattern")
        return self._find(texts, compiled(texts, vars), models, max_rows, Deadline.after(timeout))

    def exist(self, patterns: str | Sequence[str], models: Models_ = None) -> bool:
        """True if the conjunction of patterns has at least one match."""
        texts = tuple(as_list(patterns))
        if not texts:
            raise KbError("exist needs at least one pattern")
        return self._exist(compiled(texts, None), models)

    def lookup(self, query: str, models: Models_ = None) -> list[list[str]]:
        """``[[name, type], ...]``: exact matches first, then approximate ones (§3.4)."""
        if not isinstance(query, str):
            raise KbError(f"lookup takes a string, got {query!r}")
        return self._lookup(query, models)

    def about(self, term: str, models: Models_ = None) -> list[list[Any]]:
        """Every statement that mentions ``term`` (its name, or a literal's text)."""
        return self._about(optional_term(term), term, models)

    def details(self, term: str, models: Models_ = None, origin: bool = False) -> dict[str, Any]:
        """kb-compat §3.3; with ``origin``, also ``"asserted"``: one flag per relation, true when
        it is asserted in the model, false when it is only inferred."""
        return self._details(parse_term(term), models, origin)

    def label(self, term: str, lang: str | None = None, models: Models_ = None) -> str:
        """The term's label in ``lang`` (else any), or its name when it has none."""
        if lang is not None and not isinstance(lang, str):
            raise KbError(f"lang must be a language code such as 'en', got {lang!r}")
        return self._label(parse_term(term), lang, models)

    def classesof(self, term: str, direct: bool = False, models: Models_ = None) -> list[str]:
        """The classes of ``term`` (with ``direct``, only the most specific ones)."""
        return self._classes_of(parse_term(term), direct, models)

    def all_classes(self, direct: bool = False, model: str | None = None) -> dict[str, list[str]]:
        """``classesof`` of every term that has a class, at once (one model): what a view of the
        whole KB reads, rather than asking term by term."""
        model_names(model)
        return self._all_classes(direct, model)

    def all_labels(self, lang: str | None = None, model: str | None = None) -> dict[str, str]:
        """``label`` of every term that has an ``rdfs:label``, at once (one model)."""
        if lang is not None and not isinstance(lang, str):
            raise KbError(f"lang must be a language code such as 'en', got {lang!r}")
        model_names(model)
        return self._all_labels(lang, model)

    def sparql(self, query: str, model: str | Sequence[str] | None = None, *,
               timeout: float | None = None, max_rows: int | None = None) -> dict[str, Any]:
        """Read-only SPARQL 1.1 on one model: W3C JSON results plus the ``query`` (§3.7).
        ``timeout`` (seconds, waiting for the KB included) stops it with
        ``kb.errors.QueryTimeout``; more than ``max_rows`` rows (or triples of a graph) is
        ``kb.errors.TooManyRows``."""
        return to_json(self._sparql_result(query, model, Deadline.after(timeout), max_rows), query)

    def sparql_serialize(self, query: str, fmt: str | Callable[[str], str], model: str | None = None, *,
                         timeout: float | None = None, max_rows: int | None = None) -> tuple[str, bytes]:
        """Run a read-only query and serialise its result (``json``, ``xml``, ``csv``, ``tsv``
        for SELECT/ASK; RDF formats for CONSTRUCT/DESCRIBE), or in the format ``fmt`` chooses
        for the result type (SELECT, ASK, CONSTRUCT, DESCRIBE), so that the query is parsed
        once; returns (result type, bytes). ``timeout`` and ``max_rows`` as for ``sparql``."""
        result = self._sparql_result(query, model, Deadline.after(timeout), max_rows)
        return result.type, serialize_result(result, fmt if isinstance(fmt, str) else fmt(result.type))

    def export(self, fmt: str = "turtle", model: str | None = None, inferred: bool = False) -> bytes:
        """A model's asserted (or, with ``inferred``, materialised) triples in an RDF format."""
        name = export_format(fmt).name
        return serialize(self._triples(model, inferred), name)

    def save(self, path: str | Path, basename: str = "kb", models: Models_ = None) -> list[str]:
        """Write each model's asserted triples as RDF/XML to ``path/basename-<model>.rdf``."""
        folder = Path(path)
        if not folder.is_dir():
            raise KbError(f"cannot save to {str(path)!r}: not a directory")
        written = []
        for name, triples in self._asserted_by_model(models):
            target = folder / f"{basename}-{name}.rdf"
            target.write_bytes(serialize(triples, "xml"))
            written.append(str(target))
        return written

    def size(self, model: str | None = None, inferred: bool = True) -> int:
        """The number of triples of one model (with ``inferred``, of its closure)."""
        return self._size(model, inferred)

    def is_asserted(self, stmt: str, model: str | None = None) -> bool:
        """True if the statement was asserted (not only inferred) in the model."""
        return self._is_asserted(parse_ground(stmt), model)

    # --- writes ---------------------------------------------------------------------------

    def update(self, stmts: str | Sequence[str], models: Models_ = None, lifespan: float = 0) -> None:
        """Add statements; a functional property's new value replaces the old one (§3.5)."""
        self._writable()
        texts = as_list(stmts)
        with paused(len(texts)):  # parsing a bulk update allocates as much as applying it
            triples = [parse_ground(s) for s in texts]
        model_names(models)
        self._update(texts, triples, models, lifespan_seconds(lifespan))

    add = update

    def remove(self, stmts: str | Sequence[str], models: Models_ = None) -> int:
        """Retract statements; statements with variables are one conjunction whose every
        match is retracted (K12). Facts that are only inferred stay (they are derived again).
        Returns the number of asserted triples removed, over all the models written."""
        self._writable()
        texts = as_list(stmts)
        ground: list[Triple] = []
        patterns: list[str] = []
        for text in texts:
            pattern = parse_patterns([text])[0]
            if any(isinstance(t, Variable) for t in pattern):
                patterns.append(text)
            else:
                ground.append(pattern)  # type: ignore[arg-type]  # no variables in it
        model_names(models)
        query = compiled(tuple(patterns), None) if patterns else None
        return self._remove(texts, ground, query, models)

    retract = remove

    def apply(self, add: Sequence[str] = (), remove: Sequence[str] = (), models: Models_ = None,
              lifespan: float = 0) -> None:
        """Retract ``remove`` and assert ``add`` (ground statements) as ONE batch: one revision,
        one reasoning pass, one event evaluation. A perception tick or a scene diff uses this."""
        self._writable()
        added_texts, removed_texts = as_list(add), as_list(remove)
        with paused(len(added_texts) + len(removed_texts)):
            added = [parse_ground(s) for s in added_texts]
            removed = [parse_ground(s) for s in removed_texts]
        model_names(models)
        self._apply((added_texts, added), (removed_texts, removed), models, lifespan_seconds(lifespan))

    def apply_models(self, changes: Mapping[str, Changes], lifespan: float = 0) -> None:
        """Each named model's own ``remove`` retracted and ``add`` asserted, all as ONE batch
        (``{"person_bob": {"add": [...]}, "default": {"add": [...], "remove": [...]}}``): one
        revision, one commit; refused, no model changed. What a person said becomes their belief and
        the robot's knowledge this way, or neither does."""
        self._writable()
        texts = model_changes(changes)
        with paused(sum(len(a) + len(r) for a, r in texts.values())):
            parsed = {name: ([parse_ground(s) for s in add], [parse_ground(s) for s in remove])
                      for name, (add, remove) in texts.items()}
        self._apply_models(texts, parsed, lifespan_seconds(lifespan))

    def clear(self, keep_defaults: bool = True) -> None:
        """Drop every model's facts; the default ontology stays unless ``keep_defaults=False``
        (K5). Subscriptions stay and see the facts disappear."""
        self._writable()
        self._clear(keep_defaults)

    def load(self, uri: str | Path, models: Models_ = None) -> None:
        """Add the triples of a local RDF file (any rdflib format) as one batch. The file is read
        here, where the caller named it (a replica's writer may run on another machine)."""
        self._writable()
        if not isinstance(uri, str | Path):
            raise KbError(f"load takes a file path or file:// URI, got {uri!r}")
        data, fmt, source = read_location(str(uri))
        self._load(data, fmt, parse_data(data, fmt, source=source), models)

    def load_data(self, data: str | bytes, fmt: str = "turtle", models: Models_ = None) -> None:
        """Add the triples of an RDF document given as text (turtle, xml, json-ld, nt, ...)."""
        self._writable()
        self._load(data, fmt, parse_data(data, fmt), models)

    def sparql_update(self, update: str, models: Models_ = None) -> None:
        """Apply SPARQL INSERT DATA / DELETE DATA as ONE batch (no functional replacement);
        other update forms are refused (``kb.errors.UnsupportedUpdate``) before any change."""
        self._writable()
        added, removed = parse_update(update)
        model_names(models)
        self._sparql_update(update, added, removed, models)

    # --- events ---------------------------------------------------------------------------

    def subscribe(self, patterns: str | Sequence[str], callback: Callback, one_shot: bool = False,
                  models: Models_ = None, *, timeout: float | None = None, max_rows: int | None = None,
                  on_error: ErrorCallback | None = None) -> str:
        """Call ``callback(rows)`` with the new rows after each change; returns ``evt_<md5>``.
        With ``timeout`` (seconds) or ``max_rows``, every evaluation is bounded: the first one
        (waiting for the KB included) raises ``QueryTimeout`` or ``TooManyRows`` and nothing is
        subscribed; a later one past them ends the subscription and calls ``on_error(error)``
        (kb.events). A replica's callbacks run on its polling thread."""
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
        self._subscribe(sub_id, query, names, one_shot, callback, budget, on_error)
        return sub_id

    @abstractmethod
    def unsubscribe(self, sub_id: str) -> bool:
        """Stop a subscription; False if there was none of that id."""

    # --- the primitives -------------------------------------------------------------------

    @abstractmethod
    def _read_models(self, models: Models_) -> list[M]:
        """The models a read names (none: the default model; ``"all"``: every one); an unknown
        name is a ``KbError``."""

    def _one_model(self, models: Models_) -> M:
        found = self._read_models(models)
        if len(found) != 1:
            raise KbError("this call takes exactly one model")
        return found[0]

    def _writable(self) -> None:
        """Raise ``KbError`` when this KB takes no writes (a read replica without a writer):
        called first by every write, so that is what such a write is told, whatever its input."""

    @abstractmethod
    def _find(self, texts: tuple[str, ...], query: Query, models: Models_, max_rows: int | None,
              deadline: Deadline | None) -> list[Any]: ...

    @abstractmethod
    def _exist(self, query: Query, models: Models_) -> bool: ...

    @abstractmethod
    def _lookup(self, query: str, models: Models_) -> list[list[str]]: ...

    @abstractmethod
    def _about(self, node: Node | None, raw: str, models: Models_) -> list[list[Any]]: ...

    @abstractmethod
    def _details(self, node: Node, models: Models_, origin: bool) -> dict[str, Any]: ...

    @abstractmethod
    def _label(self, node: Node, lang: str | None, models: Models_) -> str: ...

    @abstractmethod
    def _classes_of(self, node: Node, direct: bool, models: Models_) -> list[str]: ...

    def _all_classes(self, direct: bool, model: str | None) -> dict[str, list[str]]:
        """From the model's triples; a backend with an index of its own answers faster."""
        types = TripleIndex(by_object=False)
        for s, p, o in self._triples(model, inferred=not direct):
            if p == RDF.type:
                types.add(s, p, o)
        return describe.all_classes(types, types, direct)

    def _all_labels(self, lang: str | None, model: str | None) -> dict[str, str]:
        labels = TripleIndex(by_object=False)
        for s, p, o in self._triples(model, inferred=True):
            if p == RDFS.label:
                labels.add(s, p, o)
        return describe.all_labels(labels, lang)

    @abstractmethod
    def _sparql_result(self, query: str, model: Models_, deadline: Deadline | None,
                       max_rows: int | None) -> Result:
        """The whole result, read: it no longer reads the KB once returned."""

    @abstractmethod
    def _triples(self, model: str | None, inferred: bool) -> list[Triple]: ...

    @abstractmethod
    def _asserted_by_model(self, models: Models_) -> Iterable[tuple[str, list[Triple]]]: ...

    @abstractmethod
    def _size(self, model: str | None, inferred: bool) -> int: ...

    @abstractmethod
    def _is_asserted(self, triple: Triple, model: str | None) -> bool: ...

    @abstractmethod
    def _update(self, texts: list[str], triples: list[Triple], models: Models_, lifespan: float) -> None: ...

    @abstractmethod
    def _remove(self, texts: list[str], ground: list[Triple], patterns: Query | None,
                models: Models_) -> int: ...

    @abstractmethod
    def _apply(self, add: tuple[list[str], list[Triple]], remove: tuple[list[str], list[Triple]],
               models: Models_, lifespan: float) -> None: ...

    @abstractmethod
    def _apply_models(self, texts: dict[str, tuple[list[str], list[str]]],
                      changes: dict[str, tuple[list[Triple], list[Triple]]], lifespan: float) -> None:
        """Per model (add, remove), as the caller wrote them and parsed."""

    @abstractmethod
    def _clear(self, keep_defaults: bool) -> None: ...

    @abstractmethod
    def _load(self, data: str | bytes, fmt: str, triples: Sequence[Triple], models: Models_) -> None: ...

    @abstractmethod
    def _sparql_update(self, update: str, added: Sequence[Triple], removed: Sequence[Triple],
                       models: Models_) -> None: ...

    @abstractmethod
    def _subscribe(self, sub_id: str, query: Query, names: list[str], one_shot: bool,
                   callback: Callback, budget: Budget, on_error: ErrorCallback | None) -> None: ...
