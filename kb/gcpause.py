"""Cyclic garbage collection paused while a bulk change runs, and kept off what lives long.

A bulk load allocates millions of tuples, dicts and sets that all stay alive. CPython's cyclic
collector runs every few hundred container allocations and walks the young objects each time, and
now and then the whole heap: a quarter of a 100k load's time, for no garbage (the index, the
closure and the deltas hold no reference cycles). The collector is paused for a large change and
restored after it, however the change ends; a small change is not worth the switch.

Once a process has built what it keeps for its whole life (a service's KB and the dialogue's view
of it), `settle` moves it out of the collector's way: its full passes, every so often, walked the
whole heap (0.3 s at 100k statements, seconds at 300k), a pause for whatever ran then.
"""

from __future__ import annotations

import gc
from collections.abc import Iterator
from contextlib import contextmanager

#: Statements from which a change is large enough to pause the collector for.
BULK = 1_000


@contextmanager
def paused(size: int) -> Iterator[None]:
    """No cyclic collection while the block runs, if ``size`` statements make it a bulk change
    and the collector is on (a caller that turned it off keeps it off)."""
    if size < BULK or not gc.isenabled():
        yield
        return
    gc.disable()
    try:
        yield
    finally:
        gc.enable()


def settle() -> None:
    """What is alive now lives as long as the process: never walked by the collector again
    (``gc.freeze``; freed as ever when its last reference goes). For a service that has built its
    KB and its grounding, not for a library: a reference cycle frozen is never collected."""
    gc.freeze()
