"""The lifespan reaper: a thread that retracts statements when their lifespan ends.

It owns no state of the KB: it asks the writer's lifespans when the next one falls due, sleeps
until then (or until a new lifespan wakes it), and calls the writer's ``expire``, which retracts
them as one commit. A failing retraction (a full disk) backs off and is reported in ``status``.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable

from kb.errors import KbError, StorageFull
from kb.lifespan import Expiries
from kb.status import StatusCell

log = logging.getLogger(__name__)

MAX_EXPIRY_BACKOFF = 30.0  # seconds between attempts to retract expired statements that keep failing


class Reaper:
    """Runs ``expire`` whenever a lifespan in ``expiries`` falls due, on its own daemon thread."""

    def __init__(self, lock: threading.RLock, expiries: Expiries, expire: Callable[[], object],
                 clock: Callable[[], float]) -> None:
        self._lock = lock
        self._expiries = expiries
        self._expire = expire
        self._clock = clock
        self._thread: threading.Thread | None = None
        self._wake = threading.Event()
        self._closed = threading.Event()
        self.status = StatusCell()  # for /health

    def wake(self) -> None:
        """A lifespan was set: start the thread if it is not running, and let it look again."""
        if self._thread is None and not self._closed.is_set():
            self._thread = threading.Thread(target=self._run, name="kb-expiry", daemon=True)
            self._thread.start()
        self._wake.set()

    def _run(self) -> None:
        while not self._closed.is_set():
            with self._lock:
                due = self._expiries.next_due()
            delay = 1.0 if due is None else min(1.0, max(0.0, due - self._clock()))
            self._wake.wait(delay)
            self._wake.clear()
            if not self._closed.is_set():
                try:
                    self._expire()
                except (KbError, OSError) as exc:  # e.g. a full disk: the statements stay due
                    delay = min(MAX_EXPIRY_BACKOFF, 2.0 ** self.status.get().failures)
                    code = "storage_full" if isinstance(exc, StorageFull) else "expiry_failed"
                    self.status.failed(code, f"expired statements could not be retracted "
                                             f"({exc}); retrying in {delay:g} s", retry_in=delay)
                    log.warning("expired statements could not be retracted; retrying in %g s: %s", delay, exc)
                    self._closed.wait(delay)
                else:
                    if not self.status.get().ok:
                        self.status.succeeded()

    def close(self) -> None:
        self._closed.set()
        self._wake.set()
        if self._thread is not None:
            self._thread.join(timeout=2.0)
            self._thread = None
