"""Intents pushed to the middleware as they are emitted: SSE, WebSocket, and the buffer as JSON."""

from __future__ import annotations

import time
from typing import Annotated, Any

from fastapi import APIRouter, Depends, Header, Query, WebSocket
from fastapi.responses import StreamingResponse
from pydantic import BaseModel, ConfigDict, Field
from sse_starlette import EventSourceResponse
from starlette.concurrency import run_in_threadpool
from starlette.requests import HTTPConnection

from api.auth import authorise, token_from_header
from api.deps import ReadAccess, ServicesDep, StreamReadAccess, WriteAccess, services_of
from api.errors import ApiError, error_body
from api.intentstream import open_reader, resume_after, serve_websocket, stream_response, websocket_query
from api.services import Services
from dialogue.intents import Intent
from dialogue.pushed.bus import IntentBus
from dialogue.pushed.events import Emitted as Pushable
from dialogue.pushed.events import IntentFilter, Origin
from dialogue.pushed.incoming import IncomingError, IncomingTooLarge, check_incoming

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


def _bus_of(services: Services) -> IntentBus:
    if services.bus is None:  # a reader forwards /intents to the writer before routing
        raise ApiError(503, "intents_elsewhere", "the intent stream is kept by the writer service")
    return services.bus


async def _bus(conn: HTTPConnection) -> IntentBus:
    # (async: FastAPI runs a plain function dependency on its thread pool, a hop per request)
    return _bus_of(services_of(conn))


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


class Emitted(BaseModel):
    model_config = ConfigDict(extra="forbid")
    origin: Origin = "dialogue"
    intent: Intent = Field(description="the Intent JSON shape")
    dialogue_id: str | None = None
    response: str = Field(default="", description="what the robot says with it")
    time: float | None = Field(default=None, ge=0, allow_inf_nan=False,
                               description="when it was emitted (seconds since the epoch); default: now")


class Published(BaseModel):
    seq: int = Field(description="its number on the stream")
    stream: str = Field(description="the stream's id (hello's)")


@router.post("", dependencies=[WriteAccess])
async def publish(body: Emitted, bus: Bus, services: ServicesDep) -> Published:
    """Push an intent on the stream, numbered after every other: how a read replica hands the
    intents of the turns it answers to the writer's stream, the deployment's one. The intent must be
    an hri_actions_msgs/Intent constant with its roles, each entity role naming something of the KB
    (422 ``invalid_intent``), and at most ``intents.max_intent_bytes`` of JSON (413)."""
    when = body.time if body.time is not None else time.time()
    emitted = Pushable(body.origin, body.intent, body.dialogue_id, body.response, when)
    try:
        limit = services.settings.intents.max_intent_bytes
        await run_in_threadpool(check_incoming, services.kb, emitted, limit)
    except IncomingTooLarge as exc:
        raise ApiError(413, "intent_too_large", str(exc)) from exc
    except IncomingError as exc:
        raise ApiError(422, "invalid_intent", str(exc)) from exc
    event = bus.publish(emitted.origin, emitted.intent, emitted.dialogue_id, emitted.response, emitted.time)
    return Published(seq=event.seq, stream=bus.stream)


@router.websocket("/ws")
async def stream_ws(websocket: WebSocket, services: ServicesDep) -> None:
    """The stream over a WebSocket: one JSON message per event, with its ``"event"``; the query
    takes the stream's ``after`` and filters."""
    await websocket.accept()
    presented = token_from_header(websocket.headers.get("authorization"))
    try:
        authorise(services.settings, presented or websocket.query_params.get("access_token"), write=False)
        bus = _bus_of(services)
        reader = open_reader(bus, *websocket_query(websocket.query_params))
    except ApiError as exc:
        await websocket.send_json(error_body(exc.status, exc.code, exc.message, exc.details))
        await websocket.close(code=1013 if exc.status in (429, 503) else 1008, reason=exc.code)
        return
    await serve_websocket(websocket, bus, reader)
