"""What the dialogue manager tells others after each turn: the turn's record, for observers.

Observers (the intent stream, each person's memory) are called in order once a turn has its result
(a late turn's polite fallback included); one that fails is logged and never fails the turn.
"""

from __future__ import annotations

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


async def notify(observers: Sequence[TurnObserver], record: TurnRecord) -> None:
    for observer in observers:
        try:
            await observer(record)
        # Observers are other components' code (as KB subscribers are): whatever one raises is
        # logged, and the turn, already answered, and the other observers go on.
        except Exception:
            log.exception("a turn observer failed on dialogue %s", record.dialogue_id)
