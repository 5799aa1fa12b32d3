"""How a piece of I/O or background work is doing, for ``/health``.

Work that can fail while the service runs (the journal on a full disk, compaction, a store
mirror, a model worker) keeps a ``StatusCell`` and registers a probe with the service's
``Components`` (one registry per service, not a global), which ``/health`` renders: a component
that is not ok makes the service degraded, with its reason.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from typing import Any


@dataclass(frozen=True)
class ComponentStatus:
    """``ok``, or why not (``code`` for machines, ``reason`` for people) and since when."""

    ok: bool = True
    code: str = ""
    reason: str = ""
    failures: int = 0  # consecutive
    since: float | None = None  # wall-clock time of the first of these failures
    retry_in: float | None = None  # seconds, for work that retries by itself

    def as_dict(self) -> dict[str, Any]:
        return {k: v for k, v in asdict(self).items() if v not in (None, "", 0) or k == "ok"}


class StatusCell:
    """The latest status of one component, safe to update from any thread."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._status = ComponentStatus()

    def get(self) -> ComponentStatus:
        with self._lock:
            return self._status

    def succeeded(self) -> None:
        with self._lock:
            self._status = ComponentStatus()

    def failed(self, code: str, reason: str, retry_in: float | None = None) -> ComponentStatus:
        with self._lock:
            previous = self._status
            self._status = ComponentStatus(
                ok=False, code=code, reason=reason, failures=previous.failures + 1,
                since=previous.since if previous.since is not None else time.time(), retry_in=retry_in)
            return self._status


Probe = Callable[[], ComponentStatus]


class Components:
    """Named status probes of one service."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._probes: dict[str, Probe] = {}

    def register(self, name: str, probe: Probe) -> None:
        with self._lock:
            self._probes[name] = probe

    def unregister(self, name: str) -> None:
        with self._lock:
            self._probes.pop(name, None)

    def report(self) -> dict[str, ComponentStatus]:
        with self._lock:
            probes = dict(self._probes)
        return {name: probe() for name, probe in sorted(probes.items())}
