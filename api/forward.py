"""A reader process's way to the writer: KB writes over the writer's REST API, and a proxy for
what only the writer holds (the scene, the commit feed, the intent stream).

With a shared SPARQL store, exactly one service process (the writer) holds the reasoner. A
reader answers queries from the store (kb.sparqlstore.remote.RemoteKB) and hands every write to
the writer through ``api.client.ServiceClient``; the writer updates the store before it answers, so
the reader's next read sees the write. The writer's refusals come back unchanged (same status, code
and message); when the writer cannot be reached the request fails with 503 and nothing is written.

The intent stream is the writer's too (a reader hands it the intents of its turns: api.relay), so
``/intents`` — the buffer, the SSE stream and the WebSocket — is the writer's, seen through any
process with one numbering.
"""

from __future__ import annotations

import contextlib
import json

import anyio
import httpx
from starlette.types import ASGIApp, Message, Receive, Scope, Send
from starlette.websockets import WebSocket
from websockets.asyncio.client import ClientConnection, connect
from websockets.exceptions import ConnectionClosed, InvalidHandshake, InvalidURI

from api.errors import error_body

#: Paths a reader forwards as they are: the scene lives in the writer, and so do the commit feed
#: and the intent stream.
FORWARDED = ("/scene", "/kb/changes", "/intents")
#: Request headers a forwarded WebSocket carries to the writer (its token).
WEBSOCKET_HEADERS = (b"authorization",)
#: Seconds to open a connection to the writer.
CONNECT_TIMEOUT = 30.0
#: Close codes that say a connection ended without a closing handshake: never sent in one.
UNSENDABLE = frozenset({1005, 1006, 1015})


class WriterProxy:
    """ASGI middleware of a reader: requests under ``FORWARDED`` paths go to the writer as they
    are (method, query, headers, body), and its answer comes back streamed (SSE included);
    WebSockets there are joined to one opened to the writer, message for message."""

    def __init__(self, app: ASGIApp, writer_url: str) -> None:
        self.app = app
        self.writer_url = writer_url.rstrip("/")
        self._http: httpx.AsyncClient | None = None

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "lifespan":
            await self.app(scope, receive, self._closing(send))
        elif scope["type"] in ("http", "websocket") and _forwarded(scope["path"]):
            if scope["type"] == "http":
                await self._http_request(scope, receive, send)
            else:
                await self._websocket(scope, receive, send)
        else:
            await self.app(scope, receive, send)

    async def _http_request(self, scope: Scope, receive: Receive, send: Send) -> None:
        if self._http is None:
            # No read timeout: the commit feed and the intent stream stay open.
            self._http = httpx.AsyncClient(base_url=self.writer_url,
                                           timeout=httpx.Timeout(CONNECT_TIMEOUT, read=None))
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
            async with anyio.create_task_group() as group:
                # A stream ends when its client goes (the server then drops what is sent quietly):
                # the writer's stream is closed too, rather than read on for nobody.
                async def watch_client() -> None:
                    while (await receive())["type"] != "http.disconnect":
                        pass
                    group.cancel_scope.cancel()

                group.start_soon(watch_client)
                await _relay_response(response, send)
                group.cancel_scope.cancel()
        finally:
            await response.aclose()

    async def _websocket(self, scope: Scope, receive: Receive, send: Send) -> None:
        client = WebSocket(scope, receive, send)
        await client.accept()
        query = scope["query_string"].decode("latin-1")
        url = "ws" + self.writer_url[len("http"):] + scope["path"] + (f"?{query}" if query else "")
        headers = [(k.decode("latin-1"), v.decode("latin-1")) for k, v in scope["headers"]
                   if k.lower() in WEBSOCKET_HEADERS]
        try:
            writer = await connect(url, additional_headers=headers, open_timeout=CONNECT_TIMEOUT)
        except (OSError, TimeoutError, InvalidHandshake, InvalidURI) as exc:
            message = f"the writer service at {self.writer_url} cannot be reached: {exc}"
            await client.send_json(error_body(503, "writer_unavailable", message))
            await client.close(code=1013, reason="writer_unavailable")
            return
        async with writer:
            if not await _join(client, writer):  # the writer ended it: so does the proxy, as it did
                code = writer.close_code
                if code is None or code in UNSENDABLE:  # it went away without a word
                    code, reason = 1013, "writer_unavailable"
                else:
                    reason = writer.close_reason or ""
                with contextlib.suppress(RuntimeError, OSError):  # unless the client went meanwhile
                    await client.close(code=code, reason=reason)

    def _closing(self, send: Send) -> Send:
        """``send`` that closes the pooled connections to the writer once the app has shut down."""
        async def closing_send(message: Message) -> None:
            if message["type"] == "lifespan.shutdown.complete" and self._http is not None:
                await self._http.aclose()
                self._http = None
            await send(message)
        return closing_send


async def _relay_response(response: httpx.Response, send: Send) -> None:
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


async def _join(client: WebSocket, writer: ClientConnection) -> bool:
    """Pass messages both ways until either side ends; True when the client went first."""
    gone = False
    async with anyio.create_task_group() as group:
        async def from_client() -> None:
            nonlocal gone
            try:
                while (message := await client.receive())["type"] != "websocket.disconnect":
                    data = message.get("text") if message.get("text") is not None else message.get("bytes")
                    if data is not None:
                        await writer.send(data)
                gone = True
            except ConnectionClosed:
                pass
            group.cancel_scope.cancel()

        async def from_writer() -> None:
            try:
                async for data in writer:
                    if isinstance(data, str):
                        await client.send_text(data)
                    else:
                        await client.send_bytes(data)
            except ConnectionClosed:
                pass
            group.cancel_scope.cancel()

        group.start_soon(from_client)
        group.start_soon(from_writer)
    return gone


def _forwarded(path: str) -> bool:
    return any(path == p or path.startswith(p + "/") for p in FORWARDED)


async def _send_error(send: Send, message: str) -> None:
    payload = json.dumps(error_body(503, "writer_unavailable", message)).encode()
    start: Message = {"type": "http.response.start", "status": 503,
                      "headers": [(b"content-type", b"application/json")]}
    await send(start)
    await send({"type": "http.response.body", "body": payload})
