"""A worker thread fed by a KB's commits: what the initiative and the memory's reconciler share.

The KB calls its commit listeners under its lock, so a listener must only look at the commit and
queue what matters; the work that reads or writes the KB runs on the follower's own thread, one item
at a time, in commit order. The queue is bounded: past it, a burst loses its newest items (logged).
A KB that reports no commits (a read replica) has nothing to follow: the writer, which every write
goes through, does the work.
"""

from __future__ import annotations

import logging
import queue
import threading
from collections.abc import Callable, Iterable
from typing import Any, Generic, TypeVar

from kb import KbError
from kb.protocol import KnowledgeBase

log = logging.getLogger(__name__)

T = TypeVar("T")


class _Stop:
    """The item that ends the worker."""


_STOP = _Stop()


class CommitFollower(Generic[T]):
    """`pick` turns each commit into items (under the KB's lock: cheap, no KB access); `handle`
    does each item's work on the worker thread. A KbError from `handle` is logged and the next
    item goes on."""

    def __init__(self, kb: KnowledgeBase, name: str, pick: Callable[[Any], Iterable[T]],
                 handle: Callable[[T], None], max_pending: int) -> None:
        self.kb = kb
        self.name = name
        self._pick = pick
        self._handle = handle
        self._pending: queue.Queue[T | _Stop] = queue.Queue(max_pending)
        self._thread: threading.Thread | None = None
        self._unwatch: Callable[[], None] | None = None

    def start(self) -> bool:
        """Follow the KB's commits; False when it reports none (a read replica)."""
        on_commit = getattr(self.kb, "on_commit", None)
        if not callable(on_commit):
            return False
        self._thread = threading.Thread(target=self._work, name=self.name, daemon=True)
        self._thread.start()
        self._unwatch = on_commit(self._commit)
        return True

    def stop(self) -> None:
        if self._unwatch is not None:
            self._unwatch()
            self._unwatch = None
        if self._thread is not None:
            self._pending.put(_STOP)
            self._thread.join(timeout=5)
            self._thread = None

    def join(self) -> None:
        """Wait until every item queued so far has been handled."""
        self._pending.join()

    def _commit(self, commit: Any) -> None:
        for item in self._pick(commit):
            try:
                self._pending.put_nowait(item)
            except queue.Full:
                log.warning("%s: too many changes at once; %s not handled", self.name, item)

    def _work(self) -> None:
        while not isinstance(item := self._pending.get(), _Stop):
            try:
                self._handle(item)
            except KbError as exc:
                log.warning("%s: %s not handled: %s", self.name, item, exc)
            finally:
                self._pending.task_done()
        self._pending.task_done()
