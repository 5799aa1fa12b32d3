"""What the dialogue manager tells others after each turn: the turn's record, for observers.

Observers (the intent stream, each person's memory) are called in order once a turn has its result
(a late turn's polite fallback included); one that fails is logged and never fails the turn. The
turn's deadline covers them too: an observer still running at the deadline (a memory write that
waits for a KB busy with a long load) goes on after the reply, which does not wait for it.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Awaitable, Callable, Sequence
from dataclasses import dataclass

from dialogue.engine import TurnResult

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class TurnRecord:
    dialogue_id: str
    user_id: str
    text: str
    result: TurnResult
    #: Wall-clock time the turn ended (seconds since the epoch).
    at: float


TurnObserver = Callable[[TurnRecord], Awaitable[None]]


async def notify(observers: Sequence[TurnObserver], record: TurnRecord, by: float | None = None,
                 late: set[asyncio.Task[None]] | None = None) -> None:
    """Tell each observer of the turn, in order; with ``by`` (the event loop's clock), return by
    then, an observer still running going on in the background (kept in ``late`` until done)."""
    loop = asyncio.get_running_loop()
    for observer in observers:
        task = loop.create_task(_observe(observer, record))
        # Even past the deadline, each observer gets its first step: one that does not wait (the
        # intent stream's) is done before the reply.
        remaining = None if by is None else max(0.0, by - loop.time())
        _done, pending = await asyncio.wait({task}, timeout=remaining)
        if pending:
            log.warning("a turn observer of dialogue %s is still running at the turn's deadline; it "
                        "goes on after the reply", record.dialogue_id)
            if late is not None:
                late.add(task)
                task.add_done_callback(late.discard)


async def _observe(observer: TurnObserver, record: TurnRecord) -> None:
    try:
        await observer(record)
    # Observers are other components' code (as KB subscribers are): whatever one raises is
    # logged, and the turn, already answered, and the other observers go on.
    except Exception:
        log.exception("a turn observer failed on dialogue %s", record.dialogue_id)
