"""The lifespan reaper: it expires what falls due, backs off on failure and stops on close."""

from __future__ import annotations

import threading
import time

from rdflib import URIRef

from kb.errors import StorageFull
from kb.lifespan import Expiries
from kb.reaper import Reaper
from tests.waiting import until

TRIPLE = (URIRef("urn:p"), URIRef("urn:sees"), URIRef("urn:q"))


def test_it_expires_a_statement_when_its_lifespan_ends() -> None:
    lock, expiries, popped = threading.RLock(), Expiries(), []
    reaper = Reaper(lock, expiries, lambda: popped.extend(expiries.pop_due(time.time())), time.time)
    expiries.set("default", TRIPLE, time.time() + 0.05)
    reaper.wake()
    try:
        until(lambda: popped == [("default", TRIPLE)])
        assert reaper.status.get().ok
    finally:
        reaper.close()


def test_a_failing_retraction_is_reported_then_cleared_when_it_succeeds() -> None:
    failing = [True]

    def expire() -> None:
        if failing[0]:
            raise StorageFull("the disk is full (test)")

    reaper = Reaper(threading.RLock(), Expiries(), expire, time.time)
    reaper.wake()
    try:
        until(lambda: not reaper.status.get().ok)
        status = reaper.status.get()
        assert status.code == "storage_full" and status.retry_in == 1.0
        failing[0] = False
        until(lambda: reaper.status.get().ok)
    finally:
        reaper.close()


def test_close_stops_the_thread_and_a_later_wake_does_not_restart_it() -> None:
    calls: list[int] = []
    reaper = Reaper(threading.RLock(), Expiries(), lambda: calls.append(1), time.time)
    reaper.wake()
    thread = reaper._thread
    assert thread is not None and thread.is_alive()
    reaper.close()
    assert not thread.is_alive()
    reaper.wake()
    assert reaper._thread is None
