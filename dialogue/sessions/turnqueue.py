"""The turns of each dialogue, one at a time in arrival order, none waiting past its own deadline.

A turn takes its place in its dialogue's queue as it arrives (`TurnQueue.take`) and waits at most
until its deadline. A place reached is the turn's until it is released; a place not reached in time
is left to work done `later` — when the place comes, in the queue's order — while the turn answers
at once (the dialogue manager records the late turn's words then). One process only: the queue is an
asyncio.Lock per dialogue, gone once no turn holds or waits for it.

>>> import asyncio
>>> async def two_turns() -> list[str]:
...     queue, done = TurnQueue(), []
...     first = await queue.take("d1", timeout=1.0)
...     second = await queue.take("d1", timeout=0.01)  # the first still holds the dialogue
...     async def record() -> None:
...         done.append("second, recorded late")
...     queue.later(second, record)
...     done.append(f"first reached: {first.reached}, second reached: {second.reached}")
...     first.release()
...     await queue.idle()
...     return done
>>> asyncio.run(two_turns())
['first reached: True, second reached: False', 'second, recorded late']
"""

from __future__ import annotations

import asyncio
import logging
import weakref
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import Literal

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class Place:
    """A turn's place in its dialogue's queue."""

    future: asyncio.Future[Literal[True]]
    lock: asyncio.Lock

    @property
    def reached(self) -> bool:
        """The turn holds its dialogue now (`release` it when done)."""
        return self.future.done() and not self.future.cancelled()

    def release(self) -> None:
        self.lock.release()

    def give_up(self) -> None:
        """Leave the queue: a place not reached yet is withdrawn, a place reached is released."""
        if not self.future.cancel():
            self.lock.release()


def _log_failure(task: asyncio.Task[None]) -> None:
    if not task.cancelled() and task.exception() is not None:
        log.error("work left for a late dialogue turn failed", exc_info=task.exception())


class TurnQueue:
    def __init__(self) -> None:
        # One lock per dialogue with a turn under way; gone once no turn holds or waits for it.
        self._locks: weakref.WeakValueDictionary[str, asyncio.Lock] = weakref.WeakValueDictionary()
        # Work of turns answered late, waiting for their place in their dialogue's queue.
        self._late: set[asyncio.Task[None]] = set()

    def _lock(self, key: str) -> asyncio.Lock:
        lock = self._locks.get(key)
        if lock is None:
            lock = asyncio.Lock()
            self._locks[key] = lock
        return lock

    async def take(self, key: str, timeout: float) -> Place:
        """The turn's place in dialogue `key`'s queue, taken now (arrival order, whatever happens to the
        turns before it) and waited for at most `timeout` seconds: see `Place.reached`."""
        if key not in self._locks:
            # No turn holds the dialogue or waits for it: the place is reached now, without the
            # task and the rounds of the event loop that waiting for one takes.
            lock = self._locks[key] = asyncio.Lock()
            await lock.acquire()  # (a lock no one else has: never waits)
            reached: asyncio.Future[Literal[True]] = asyncio.get_running_loop().create_future()
            reached.set_result(True)
            return Place(reached, lock)
        lock = self._lock(key)
        place = Place(asyncio.ensure_future(lock.acquire()), lock)
        try:
            await asyncio.wait((place.future,), timeout=max(0.0, timeout))
        except asyncio.CancelledError:
            place.give_up()
            raise
        return place

    def later(self, place: Place, work: Callable[[], Awaitable[None]]) -> None:
        """Run `work` once the place not reached in time comes, then free it (the order is kept)."""

        async def run() -> None:
            try:
                await asyncio.shield(place.future)
            except asyncio.CancelledError:
                place.give_up()
                raise
            try:
                await work()
            finally:
                place.release()

        task = asyncio.get_running_loop().create_task(run())
        self._late.add(task)
        task.add_done_callback(self._late.discard)
        task.add_done_callback(_log_failure)

    async def idle(self) -> None:
        """Wait for the work left `later` (tests, shutdown)."""
        while self._late:
            await asyncio.gather(*self._late, return_exceptions=True)
