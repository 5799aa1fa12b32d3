"""A reader process's way to the writer: KB writes over the writer's REST API, and a proxy for
what only the writer holds (the scene, the commit feed).

With a shared SPARQL store, exactly one service process (the writer) holds the reasoner. A
reader answers queries from the store (kb.sparqlstore.remote.RemoteKB) and hands every write to
the writer through ``api.client.ServiceClient``; the writer updates the store before it answers, so
the reader's next read sees the write. The writer's refusals come back unchanged (same status, code
and message); when the writer cannot be reached the request fails with 503 and nothing is written.
"""

from __future__ import annotations

import json

import httpx
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from api.errors import error_body

#: Paths a reader forwards as they are: the scene lives in the writer, and so does the commit feed.
FORWARDED = ("/scene", "/kb/changes")


class WriterProxy:
    """ASGI middleware of a reader: requests under ``FORWARDED`` paths go to the writer as they
    are (method, query, headers, body), and its answer comes back streamed (SSE included)."""

    def __init__(self, app: ASGIApp, writer_url: str) -> None:
        self.app = app
        self.writer_url = writer_url.rstrip("/")
        self._http: httpx.AsyncClient | None = None

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "lifespan":
            await self.app(scope, receive, self._closing(send))
            return
        if scope["type"] != "http" or not _forwarded(scope["path"]):
            await self.app(scope, receive, send)
            return
        if self._http is None:
            # No read timeout: the commit feed is a stream that stays open.
            self._http = httpx.AsyncClient(base_url=self.writer_url, timeout=httpx.Timeout(30.0, read=None))
        body = b""
        more = True
        while more:
            message = await receive()
            body += message.get("body", b"")
            more = message.get("more_body", False)
        headers = [(k.decode("latin-1"), v.decode("latin-1")) for k, v in scope["headers"]
                   if k.lower() not in (b"host", b"content-length", b"connection")]
        request = self._http.build_request(scope["method"], scope["path"], headers=headers, content=body,
                                           params=scope["query_string"].decode())
        try:
            response = await self._http.send(request, stream=True)
        except httpx.HTTPError as exc:
            await _send_error(send, f"the writer service at {self.writer_url} cannot be reached: {exc}")
            return
        try:
            hop = ("content-length", "transfer-encoding", "connection")
            await send({"type": "http.response.start", "status": response.status_code,
                        "headers": [(k.encode("latin-1"), v.encode("latin-1"))
                                    for k, v in response.headers.items() if k.lower() not in hop]})
            async for chunk in response.aiter_raw():
                await send({"type": "http.response.body", "body": chunk, "more_body": True})
            await send({"type": "http.response.body", "body": b"", "more_body": False})
        except httpx.HTTPError:
            await send({"type": "http.response.body", "body": b"", "more_body": False})
        finally:
            await response.aclose()


    def _closing(self, send: Send) -> Send:
        """``send`` that closes the pooled connections to the writer once the app has shut down."""
        async def closing_send(message: Message) -> None:
            if message["type"] == "lifespan.shutdown.complete" and self._http is not None:
                await self._http.aclose()
                self._http = None
            await send(message)
        return closing_send


def _forwarded(path: str) -> bool:
    return any(path == p or path.startswith(p + "/") for p in FORWARDED)


async def _send_error(send: Send, message: str) -> None:
    payload = json.dumps(error_body(503, "writer_unavailable", message)).encode()
    start: Message = {"type": "http.response.start", "status": 503,
                      "headers": [(b"content-type", b"application/json")]}
    await send(start)
    await send({"type": "http.response.body", "body": payload})
