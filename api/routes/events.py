"""KB events: Server-Sent Events at ``GET /kb/events`` and the same over ``/kb/events/ws``.

Each event carries a JSON list of the new binding rows (kb-compat §3.6). SSE: a first
``event: subscribed`` with the subscription id, then one default (``message``) event per batch
of rows, a comment every 15 s to keep proxies open, and ``event: end`` when a one-shot
subscription has fired. WebSocket: the client first sends ``{"patterns", "one_shot", "models"}``;
the server answers ``{"subscribed": id}``, then one JSON list per batch, and closes after a
one-shot fires. Past ``limits.max_subscribers`` a new subscriber gets 429 ``too_many_subscribers``
(over WebSocket: that error object, then close code 1013, "try again later").

A subscription is evaluated within the query limits (``limits.query_timeout``,
``limits.max_rows``): one whose starting rows go past them is refused with 503 ``query_timeout``
or 413 ``too_many_rows`` (over WebSocket: that error object, then close code 1008); one whose
evaluation after a commit goes past them is ended, with SSE ``event: error`` carrying that error
object (over WebSocket: the object, then close code 1008).
"""

from __future__ import annotations

import asyncio
import json
from collections.abc import AsyncIterator
from typing import Annotated, Any

import anyio
from fastapi import APIRouter, Query, WebSocket, WebSocketDisconnect
from fastapi.responses import StreamingResponse
from pydantic import BaseModel, ConfigDict, Field, ValidationError
from starlette.concurrency import run_in_threadpool
from starlette.types import Receive, Scope, Send

from api.auth import authorise, token_from_header
from api.deps import HubDep, ServicesDep, SettingsDep, StreamReadAccess
from api.errors import ApiError, error_body, over_budget
from api.limits import check_count
from api.subscriptions import EventHub, Listener
from kb import KbError
from kb.errors import QueryTimeout, TooManyRows

router = APIRouter(prefix="/kb", tags=["events"])
KEEPALIVE_SECONDS = 15.0


class Subscription(BaseModel):
    model_config = ConfigDict(extra="forbid")
    patterns: list[str] = Field(min_length=1)
    one_shot: bool = False
    models: list[str] | None = None


def _sse(data: Any, event: str | None = None) -> str:
    head = f"event: {event}\n" if event else ""
    return f"{head}data: {json.dumps(data)}\n\n"


async def _close(hub: EventHub, listener: Listener) -> None:
    with anyio.CancelScope(shield=True):  # the client is gone; still unsubscribe
        await run_in_threadpool(hub.close, listener)


async def _stream(listener: Listener) -> AsyncIterator[str]:
    yield _sse({"id": listener.sub_id}, "subscribed")
    while True:
        try:
            rows = await asyncio.wait_for(listener.next_rows(), KEEPALIVE_SECONDS)
        except TimeoutError:
            yield ": keepalive\n\n"
            continue
        if rows is None:
            if listener.error is not None:
                yield _sse(listener.error, "error")
            else:
                yield _sse({"reason": listener.end_reason}, "end")
            return
        yield _sse(rows)


class EventStream(StreamingResponse):
    """An SSE response that releases its listener however it ends, even if it never started."""

    def __init__(self, hub: EventHub, listener: Listener) -> None:
        super().__init__(_stream(listener), media_type="text/event-stream",
                         headers={"Cache-Control": "no-cache", "X-Accel-Buffering": "no"})
        self._hub = hub
        self._listener = listener

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        try:
            await super().__call__(scope, receive, send)
        finally:
            await _close(self._hub, self._listener)


@router.get("/events", dependencies=[StreamReadAccess], response_class=StreamingResponse, responses={
    200: {"content": {"text/event-stream": {}}, "description": "a stream of new binding rows"}})
async def events(hub: HubDep, settings: SettingsDep,
                 pattern: Annotated[list[str], Query(min_length=1, description="a pattern (repeatable)")],
                 one_shot: bool = False,
                 models: Annotated[list[str] | None, Query()] = None) -> StreamingResponse:
    """Server-Sent Events: each event's ``data`` is the JSON list of new rows."""
    check_count(pattern, settings.limits.max_patterns, "patterns")
    listener = await run_in_threadpool(hub.open, pattern, one_shot, models, asyncio.get_running_loop())
    return EventStream(hub, listener)


@router.get("/changes", dependencies=[StreamReadAccess], response_class=StreamingResponse, responses={
    200: {"content": {"text/event-stream": {}}, "description": "a stream of committed changes"}})
async def changes(hub: HubDep) -> StreamingResponse:
    """Server-Sent Events, one per commit to the robot's model: ``[{"revision", "cleared",
    "added": [[s, p, o], ...], "removed": [...]}]`` (asserted and inferred), or ``"truncated":
    true`` instead of the lists when a commit changed more than 500 statements. Unlike
    ``/kb/events`` it also tells what disappeared (retractions, expiry)."""
    listener = await run_in_threadpool(hub.open_changes, asyncio.get_running_loop())
    return EventStream(hub, listener)


async def _refuse(websocket: WebSocket, error: ApiError, code: int) -> None:
    await websocket.send_json(error_body(error.status, error.code, error.message, error.details))
    await websocket.close(code=code, reason=error.code)


async def _subscribe(websocket: WebSocket, services: ServicesDep) -> Listener | None:
    """Authorise, read the subscription message and open it; on failure tell the client why."""
    settings = services.settings
    presented = token_from_header(websocket.headers.get("authorization"))
    try:
        authorise(settings, presented or websocket.query_params.get("access_token"), write=False)
        raw = await websocket.receive_text()
        try:
            request = Subscription.model_validate_json(raw)
        except ValidationError as exc:
            first = exc.errors()[0]
            where = ".".join(str(p) for p in first["loc"]) or "message"
            raise ApiError(422, "invalid_request", f"subscription message: {where}: {first['msg']}") from exc
        check_count(request.patterns, settings.limits.max_patterns, "patterns")
        return await run_in_threadpool(services.hub.open, request.patterns, request.one_shot,
                                       request.models, asyncio.get_running_loop())
    except ApiError as exc:
        await _refuse(websocket, exc, 1013 if exc.status == 429 else 1008)
    except (QueryTimeout, TooManyRows) as exc:
        await _refuse(websocket, over_budget(exc), 1008)
    except KbError as exc:
        await _refuse(websocket, ApiError(400, "kb_error", str(exc)), 1008)
    return None


@router.websocket("/events/ws")
async def events_ws(websocket: WebSocket, services: ServicesDep) -> None:
    """The SSE stream over a WebSocket (first message: the subscription)."""
    await websocket.accept()
    try:
        listener = await _subscribe(websocket, services)
    except WebSocketDisconnect:
        return
    if listener is None:
        return
    client_gone = False
    try:
        await websocket.send_json({"subscribed": listener.sub_id})
        async with anyio.create_task_group() as group:
            async def watch_client() -> None:
                nonlocal client_gone
                while (await websocket.receive())["type"] != "websocket.disconnect":
                    pass  # clients have nothing more to say; only a disconnect matters
                client_gone = True
                group.cancel_scope.cancel()

            group.start_soon(watch_client)
            while (rows := await listener.next_rows()) is not None:
                await websocket.send_json(rows)
            group.cancel_scope.cancel()
        if client_gone:
            return
        if listener.error is not None:
            await websocket.send_json(listener.error)
            await websocket.close(code=1008, reason=listener.error["code"])
        else:
            await websocket.close()
    except WebSocketDisconnect:
        pass
    finally:
        await _close(services.hub, listener)
