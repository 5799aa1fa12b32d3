"""A dialogue turn answered as Server-Sent Events, for a client whose ``Accept`` asks for
``text/event-stream`` (any other client gets the plain JSON answer, unchanged).

Events, in order:

- ``event: ack``, data ``{"verbal_ack": "..."}``: the model's spoken reply as soon as its streamed
  answer has closed that string, before the intent is generated (dialogue.earlyack). Only from a
  backend that streams, only when the answer starts with a non-empty `verbal_ack`, at most once.
  It is provisional: the final `response` is what the turn answered (the same text when the answer
  validated; otherwise a repaired reply, a clarifying question or the fallback's apology).
- ``event: response``: the full response, exactly the JSON body the endpoint returns without SSE.

A turn that cannot start (an unknown dialogue) is refused with the usual error status before any
event: the stream begins when its first event is ready. A client that goes away does not stop the
turn: it still completes and is recorded in the dialogue's history, as with the JSON answer.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import AsyncIterator, Awaitable, Callable
from typing import Any, TypeVar

from sse_starlette import EventSourceResponse, JSONServerSentEvent

from api.errors import ApiError
from api.negotiation import negotiate
from dialogue.earlyack import acks_to

log = logging.getLogger(__name__)

EVENT_STREAM = "text/event-stream"
#: JSON first: a tie (``*/*``, or both listed alike) keeps the plain answer.
_OFFERS = ("application/json", EVENT_STREAM)
T = TypeVar("T")


def wants_events(accept: str | None) -> bool:
    """True when the client names ``text/event-stream`` and prefers it to JSON (``text/*`` is not
    asking for a stream: such a client has always had JSON)."""
    if not accept or EVENT_STREAM not in accept.lower():
        return False
    try:
        return negotiate(accept, _OFFERS) == EVENT_STREAM
    except ApiError:  # accepts neither: the route answers JSON, as it always has
        return False


def _log_failure(task: asyncio.Task[Any]) -> None:
    if not task.cancelled() and task.exception() is not None:
        log.error("a streamed dialogue turn failed", exc_info=task.exception())


async def turn_events(run: Callable[[], Awaitable[T]], render: Callable[[T], Any]) -> EventSourceResponse:
    """Run the turn `run()` and answer with its events; `render` makes the final JSON body.

    Whatever `run()` raises before the first event propagates (the route maps it to its status)."""
    acks: asyncio.Queue[str] = asyncio.Queue()

    async def turn() -> T:
        with acks_to(acks.put_nowait):
            return await run()

    task = asyncio.create_task(turn())
    first_ack = asyncio.ensure_future(acks.get())
    try:
        await asyncio.wait((task, first_ack), return_when=asyncio.FIRST_COMPLETED)
    except asyncio.CancelledError:
        first_ack.cancel()
        task.cancel()
        raise
    if first_ack.done():
        ack: str | None = first_ack.result()
    else:  # the turn ended first; an ack it sent may still wait in the queue
        first_ack.cancel()
        ack = None if acks.empty() else acks.get_nowait()
    failure = task.exception() if task.done() else None
    if failure is not None:
        raise failure
    task.add_done_callback(_log_failure)

    async def events() -> AsyncIterator[JSONServerSentEvent]:
        if ack is not None:
            yield JSONServerSentEvent({"verbal_ack": ack}, event="ack")
        # Shielded: a client that disconnects cancels this stream, not the turn.
        result = await asyncio.shield(task)
        yield JSONServerSentEvent(render(result), event="response")

    return EventSourceResponse(events(), headers={"Cache-Control": "no-cache", "X-Accel-Buffering": "no"})
