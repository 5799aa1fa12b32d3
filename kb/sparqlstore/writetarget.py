"""Where a read replica (kb.sparqlstore.remote.RemoteKB) sends its writes: the one writer of the dataset.

A ``WriteTarget`` has the write methods of ``KB``. An in-process ``KB`` is one (tests and
single-process setups); a client of the writer service's REST API is another. A replica's writes
are checked by the facade (kb.facade) exactly as ``KB``'s are, before anything is sent; then
``ReplicaWrites`` hands them to the target, and a replica without one refuses them.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Protocol, runtime_checkable

from kb.arguments import Changes, Models_
from kb.errors import KbError


@runtime_checkable
class WriteTarget(Protocol):
    """The write half of the KB API (kb-compat §3.5, §3.7)."""

    def update(self, stmts: str | Sequence[str], models: Models_ = None, lifespan: float = 0) -> None: ...

    def remove(self, stmts: str | Sequence[str], models: Models_ = None) -> int:
        """Returns the number of asserted triples removed."""

    def apply(self, add: Sequence[str] = (), remove: Sequence[str] = (), models: Models_ = None,
              lifespan: float = 0) -> None: ...

    def apply_models(self, changes: Mapping[str, Changes], lifespan: float = 0) -> None: ...

    def clear(self, keep_defaults: bool = True) -> None: ...

    def load_data(self, data: str | bytes, fmt: str = "turtle", models: Models_ = None) -> None: ...

    def sparql_update(self, update: str, models: Models_ = None) -> None: ...


class ReplicaWrites:
    """A replica's way to its writer; without one, writes are refused."""

    def __init__(self, target: WriteTarget | None, store: str) -> None:
        if target is not None and not isinstance(target, WriteTarget):
            raise KbError(f"writes must be a KB or another write target, got {target!r}")
        self._target = target
        self._store = store

    @property
    def target(self) -> WriteTarget | None:
        return self._target

    def require(self) -> WriteTarget:
        """The writer; a replica without one refuses every write (its arguments were checked by
        the facade, exactly as ``KB`` checks them, before this is asked)."""
        if self._target is None:
            raise KbError(f"this KB is a read-only replica of {self._store}: send writes to the writer "
                          "(give RemoteKB a write target)")
        return self._target
