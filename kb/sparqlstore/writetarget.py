"""Where a read replica (kb.sparqlstore.remote.RemoteKB) sends its writes: the one writer of the dataset.

A ``WriteTarget`` has the write methods of ``KB``. An in-process ``KB`` is one (tests and
single-process setups); a client of the writer service's REST API is another. ``ReplicaWrites``
checks every write exactly as ``KB`` does (same parsers, so the same errors, before anything is
sent) and forwards it; a replica without a target refuses writes.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Protocol, runtime_checkable

from rdflib import Variable

from kb.arguments import Models_, compiled, lifespan_seconds, model_names
from kb.errors import KbError
from kb.rdfio import parse_data, read_location
from kb.sparql import parse_update
from kb.terms import as_list, parse_ground, parse_patterns


@runtime_checkable
class WriteTarget(Protocol):
    """The write half of the KB API (kb-compat §3.5, §3.7)."""

    def update(self, stmts: str | Sequence[str], models: Models_ = None, lifespan: float = 0) -> None: ...

    def remove(self, stmts: str | Sequence[str], models: Models_ = None) -> int:
        """Returns the number of asserted triples removed."""

    def apply(self, add: Sequence[str] = (), remove: Sequence[str] = (), models: Models_ = None,
              lifespan: float = 0) -> None: ...

    def clear(self, keep_defaults: bool = True) -> None: ...

    def load_data(self, data: str | bytes, fmt: str = "turtle", models: Models_ = None) -> None: ...

    def sparql_update(self, update: str, models: Models_ = None) -> None: ...


class ReplicaWrites:
    """Checks writes like ``KB`` and forwards them to the writer; without one, refuses them."""

    def __init__(self, target: WriteTarget | None, store: str) -> None:
        if target is not None and not isinstance(target, WriteTarget):
            raise KbError(f"writes must be a KB or another write target, got {target!r}")
        self._target = target
        self._store = store

    @property
    def target(self) -> WriteTarget | None:
        return self._target

    def _require(self) -> WriteTarget:
        if self._target is None:
            raise KbError(f"this KB is a read-only replica of {self._store}: send writes to the writer "
                          "(give RemoteKB a write target)")
        return self._target

    def update(self, stmts: str | Sequence[str], models: Models_, lifespan: float) -> None:
        target = self._require()
        texts = as_list(stmts)
        for text in texts:
            parse_ground(text)
        model_names(models)
        lifespan_seconds(lifespan)
        target.update(texts, models, lifespan)

    def remove(self, stmts: str | Sequence[str], models: Models_) -> int:
        target = self._require()
        texts = as_list(stmts)
        patterns = [text for text in texts if _has_variables(text)]
        model_names(models)
        if patterns:
            compiled(tuple(patterns), None)
        return target.remove(texts, models)

    def apply(self, add: Sequence[str], remove: Sequence[str], models: Models_, lifespan: float) -> None:
        target = self._require()
        added, removed = as_list(add), as_list(remove)
        for text in (*added, *removed):
            parse_ground(text)
        model_names(models)
        lifespan_seconds(lifespan)
        target.apply(added, removed, models, lifespan)

    def clear(self, keep_defaults: bool) -> None:
        self._require().clear(keep_defaults)

    def load(self, uri: str | Path, models: Models_) -> None:
        target = self._require()
        if not isinstance(uri, str | Path):
            raise KbError(f"load takes a file path or file:// URI, got {uri!r}")
        # The file is read here, where the caller named it, and sent as data: the writer may
        # run on another machine.
        data, fmt, source = read_location(str(uri))
        parse_data(data, fmt, source=source)
        model_names(models)
        target.load_data(data, fmt, models)

    def load_data(self, data: str | bytes, fmt: str, models: Models_) -> None:
        target = self._require()
        parse_data(data, fmt)
        model_names(models)
        target.load_data(data, fmt, models)

    def sparql_update(self, update: str, models: Models_) -> None:
        target = self._require()
        parse_update(update)
        model_names(models)
        target.sparql_update(update, models)


def _has_variables(text: str) -> bool:
    return any(isinstance(t, Variable) for t in parse_patterns([text])[0])
