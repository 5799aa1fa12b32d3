"""Waiting for what another thread, process or ROS graph does: the one helper of the tests."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TypeVar

T = TypeVar("T")


def until(check: Callable[[], T], timeout: float = 30.0, every: float = 0.01, *,
          ignoring: tuple[type[Exception], ...] = ()) -> T:
    """``check()``'s first truthy value, asked every ``every`` s; after ``timeout`` s, an
    AssertionError with its last value. An exception of ``ignoring`` means "not yet" (raised again
    once the time is up). The timeout is a safety net, far above what the wait takes."""
    end = time.monotonic() + timeout
    while True:
        try:
            value = check()
        except ignoring:
            if time.monotonic() >= end:
                raise
        else:
            if value:
                return value
            assert time.monotonic() < end, f"still {value!r} after {timeout} s"
        time.sleep(every)
