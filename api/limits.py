"""Request body size bound, as a small ASGI middleware.

A declared ``Content-Length`` over the limit is refused before anything is read; a body sent
without one (chunked) is counted as it streams and refused as soon as it passes the limit.
"""

from __future__ import annotations

import json
from collections.abc import Awaitable, Callable, MutableMapping, Sized
from typing import Any

from api.errors import ApiError, error_body

Scope = MutableMapping[str, Any]
Message = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[Message]]
Send = Callable[[Message], Awaitable[None]]
ASGIApp = Callable[[Scope, Receive, Send], Awaitable[None]]


def body_too_large(limit: int) -> ApiError:
    return ApiError(413, "body_too_large", f"the request body is larger than the limit of {limit} bytes",
                    {"limit": limit})


class BodySizeLimit:
    def __init__(self, app: ASGIApp, max_bytes: int) -> None:
        self.app = app
        self.max_bytes = max_bytes

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        declared = _content_length(scope)
        if declared is not None and declared > self.max_bytes:
            await _refuse(send, self.max_bytes)
            return
        seen = 0

        async def counted() -> Message:
            nonlocal seen
            message = await receive()
            if message["type"] == "http.request":
                seen += len(message.get("body", b""))
                if seen > self.max_bytes:
                    # Raised inside the route's body read, so the app's handler shapes the 413.
                    raise body_too_large(self.max_bytes)
            return message

        await self.app(scope, counted, send)


def _content_length(scope: Scope) -> int | None:
    for name, value in scope.get("headers", ()):
        if name == b"content-length":
            try:
                return int(value)
            except ValueError:
                return None
    return None


async def _refuse(send: Send, limit: int) -> None:
    error = body_too_large(limit)
    body = json.dumps(error_body(error.status, error.code, error.message, error.details)).encode()
    await send({"type": "http.response.start", "status": 413,
                "headers": [(b"content-type", b"application/json"),
                            (b"content-length", str(len(body)).encode()),
                            (b"connection", b"close")]})
    await send({"type": "http.response.body", "body": body})


def check_count(items: Sized, limit: int, what: str) -> None:
    """413 ``too_many_<what>`` when a request carries more items than the configured limit."""
    if len(items) > limit:
        raise ApiError(413, f"too_many_{what}", f"{len(items)} {what} in one request; the limit is {limit}",
                       {"count": len(items), "limit": limit})


def check_length(text: str, limit: int, what: str) -> None:
    """413 ``<what>_too_long`` for a text longer than the configured limit."""
    if len(text) > limit:
        raise ApiError(413, f"{what}_too_long",
                       f"the {what} has {len(text)} characters; the limit is {limit}",
                       {"length": len(text), "limit": limit})
