"""Intents pushed to the middleware as they are emitted: SSE, WebSocket, and the buffer as JSON."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, Depends, Header, Query, WebSocket
from fastapi.responses import StreamingResponse
from sse_starlette import EventSourceResponse

from api.auth import authorise, token_from_header
from api.deps import ReadAccess, ServicesDep, StreamReadAccess
from api.errors import ApiError, error_body
from api.intentstream import open_reader, resume_after, serve_websocket, stream_response, websocket_query
from dialogue.pushed.bus import IntentBus
from dialogue.pushed.events import IntentFilter

router = APIRouter(prefix="/intents", tags=["intents"])

After = Annotated[int | None, Query(ge=0, description="resume after this sequence number (replayed from "
                                   "the buffer)")]


def intent_filter(source: Annotated[list[str] | None, Query(description="intent source (repeatable)")] = None,
                  intent: Annotated[list[str] | None, Query(description="intent type (repeatable)")] = None,
                  origin: Annotated[list[str] | None, Query(description="dialogue or initiative")] = None,
                  dialogue_id: Annotated[list[str] | None, Query(description="dialogue (repeatable)")] = None,
                  ) -> IntentFilter:
    try:
        return IntentFilter.of(source or (), intent or (), origin or (), dialogue_id or ())
    except ValueError as exc:
        raise ApiError(422, "invalid_request", str(exc)) from exc


Filter = Annotated[IntentFilter, Depends(intent_filter)]


def _bus(services: ServicesDep) -> IntentBus:
    return services.bus


Bus = Annotated[IntentBus, Depends(_bus)]


@router.get("/stream", dependencies=[StreamReadAccess], response_class=StreamingResponse, responses={
    200: {"content": {"text/event-stream": {}}, "description": "hello, gap?, intent..., end"}})
async def stream(bus: Bus, flt: Filter, after: After = None,
                 last_event_id: Annotated[str | None, Header()] = None) -> EventSourceResponse:
    """Server-Sent Events: every intent emitted by a dialogue or by the robot's initiative, as it
    is emitted (see api.intentstream for the events)."""
    return stream_response(bus, open_reader(bus, flt, resume_after(after, last_event_id)))


@router.get("", dependencies=[ReadAccess])
async def buffered(bus: Bus, flt: Filter, after: After = None) -> dict[str, Any]:
    """The buffered intents after ``after`` (all of the buffer by default), for a client that polls."""
    events, gap = bus.since(after if after is not None else 0, flt)
    return {"stream": bus.stream, "last_seq": bus.last_seq, "gap": gap.as_json() if gap else None,
            "intents": [e.as_json() for e in events]}


@router.websocket("/ws")
async def stream_ws(websocket: WebSocket, services: ServicesDep) -> None:
    """The stream over a WebSocket: one JSON message per event, with its ``"event"``; the query
    takes the stream's ``after`` and filters."""
    await websocket.accept()
    presented = token_from_header(websocket.headers.get("authorization"))
    try:
        authorise(services.settings, presented or websocket.query_params.get("access_token"), write=False)
        reader = open_reader(services.bus, *websocket_query(websocket.query_params))
    except ApiError as exc:
        await websocket.send_json(error_body(exc.status, exc.code, exc.message, exc.details))
        await websocket.close(code=1013 if exc.status == 429 else 1008, reason=exc.code)
        return
    await serve_websocket(websocket, services.bus, reader)
