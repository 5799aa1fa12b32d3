"""The intent bus as Server-Sent Events and WebSocket messages (GET /intents/stream, /intents/ws).

Events, in order: `hello` (`{"stream", "last_seq", "gap"}`: which bus, its last number, and the
gap that follows if any), then `gap` when the client asked to resume after a number the buffer no
longer covers or one from before a restart (`{"first", "last", "restarted"}`), then one `intent`
per pushed intent (`id` its number, data the pushed intent: dialogue.pushed.events), and `end`
(`{"reason"}`) when the service stops or the client fell too far behind (it then resumes with
`after`, or over SSE with the `Last-Event-ID` an EventSource sends by itself on reconnecting). Over
WebSocket each message is the JSON object with an `"event"` key naming which of these it is.
"""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator
from typing import Any

import anyio
from fastapi import WebSocket, WebSocketDisconnect
from sse_starlette import EventSourceResponse, JSONServerSentEvent
from starlette.datastructures import QueryParams

from api.errors import ApiError
from dialogue.pushed.bus import IntentBus, Reader
from dialogue.pushed.events import IntentFilter

KEEPALIVE_SECONDS = 15.0
#: Digits of a sequence number: the bus numbers from the clock in milliseconds (13 digits now), so
#: a number of more is none it gave (and past 4,300 digits int() itself refuses it).
MAX_SEQ_DIGITS = 20
#: Characters of a bad value said back in the error.
_SHOWN = 40


def sequence_number(text: str, what: str) -> int:
    """The sequence number written in `text` (`what` names where it came from); ApiError 422 saying
    what is wrong when it is none."""
    if not (text.isascii() and text.isdigit()) or len(text) > MAX_SEQ_DIGITS:
        shown = text if len(text) <= _SHOWN else f"{text[:_SHOWN]}... ({len(text)} characters)"
        raise ApiError(422, "invalid_request", f"{what} {shown!r} is not a sequence number (0 or more, "
                                               f"at most {MAX_SEQ_DIGITS} digits)")
    return int(text)


def websocket_query(params: QueryParams) -> tuple[IntentFilter, int | None]:
    """The filter and resume number of a WebSocket's query (`after`, `source`, `intent`, `origin`,
    `dialogue_id`), read after the handshake so that a bad one is told as an error message (a
    refused handshake tells a client nothing). ApiError 422 saying what is wrong."""
    after = params.get("after")
    number = sequence_number(after, "after") if after is not None else None
    try:
        flt = IntentFilter.of(params.getlist("source"), params.getlist("intent"), params.getlist("origin"),
                              params.getlist("dialogue_id"))
    except ValueError as exc:
        raise ApiError(422, "invalid_request", str(exc)) from exc
    return flt, number


def resume_after(after: int | None, last_event_id: str | None) -> int | None:
    """Where an SSE client resumes: `after`, else the `Last-Event-ID` an EventSource sends by itself
    on reconnecting (ApiError 422 when it is no sequence number)."""
    if after is not None or not last_event_id:
        return after
    return sequence_number(last_event_id, "Last-Event-ID")


def open_reader(bus: IntentBus, flt: IntentFilter, after: int | None) -> Reader:
    """A reader on the running loop (429 past the bus's bound of readers)."""
    try:
        return bus.subscribe(asyncio.get_running_loop(), flt, after)
    except ValueError as exc:
        raise ApiError(429, "too_many_subscribers", str(exc), {"limit": bus.max_readers}) from exc


def hello(bus: IntentBus, reader: Reader) -> dict[str, Any]:
    return {"stream": bus.stream, "last_seq": bus.last_seq,
            "gap": reader.gap.as_json() if reader.gap is not None else None}


def stream_response(bus: IntentBus, reader: Reader) -> EventSourceResponse:
    async def events() -> AsyncIterator[JSONServerSentEvent]:
        try:
            yield JSONServerSentEvent(hello(bus, reader), event="hello")
            if reader.gap is not None:
                yield JSONServerSentEvent(reader.gap.as_json(), event="gap")
            while (event := await reader.next()) is not None:
                yield JSONServerSentEvent(event.as_json(), event="intent", id=str(event.seq))
            yield JSONServerSentEvent({"reason": reader.end_reason}, event="end")
        finally:
            bus.close(reader)

    return EventSourceResponse(events(), ping=KEEPALIVE_SECONDS,
                               headers={"Cache-Control": "no-cache", "X-Accel-Buffering": "no"})


async def serve_websocket(websocket: WebSocket, bus: IntentBus, reader: Reader) -> None:
    """Send the reader's events until it ends or the client goes; the reader is closed after."""
    try:
        await websocket.send_json({"event": "hello", **hello(bus, reader)})
        if reader.gap is not None:
            await websocket.send_json({"event": "gap", **reader.gap.as_json()})
        gone = False
        async with anyio.create_task_group() as group:
            async def watch_client() -> None:
                nonlocal gone
                while (await websocket.receive())["type"] != "websocket.disconnect":
                    pass  # clients have nothing to say; only a disconnect matters
                gone = True
                group.cancel_scope.cancel()

            group.start_soon(watch_client)
            while (event := await reader.next()) is not None:
                await websocket.send_json({"event": "intent", **event.as_json()})
            group.cancel_scope.cancel()
        if not gone:
            await websocket.send_json({"event": "end", "reason": reader.end_reason})
            await websocket.close()
    except WebSocketDisconnect:
        pass
    finally:
        bus.close(reader)
