"""The reader's WriterProxy: pass-through of what it does not forward, and a clean shutdown."""

from __future__ import annotations

import asyncio

import httpx
from starlette.types import Message, Receive, Scope, Send

from api.forward import WriterProxy


async def _lifespan_app(scope: Scope, receive: Receive, send: Send) -> None:
    assert scope["type"] == "lifespan"
    while True:
        message = await receive()
        if message["type"] == "lifespan.startup":
            await send({"type": "lifespan.startup.complete"})
        elif message["type"] == "lifespan.shutdown":
            await send({"type": "lifespan.shutdown.complete"})
            return


def test_shutdown_closes_the_connections_to_the_writer() -> None:
    async def run() -> tuple[list[str], bool]:
        proxy = WriterProxy(_lifespan_app, "http://127.0.0.1:9")
        client = httpx.AsyncClient()
        proxy._http = client
        inbox: asyncio.Queue[Message] = asyncio.Queue()
        for kind in ("lifespan.startup", "lifespan.shutdown"):
            inbox.put_nowait({"type": kind})
        sent: list[str] = []

        async def send(message: Message) -> None:
            sent.append(message["type"])

        await proxy({"type": "lifespan"}, inbox.get, send)
        return sent, client.is_closed

    sent, closed = asyncio.run(run())
    assert sent == ["lifespan.startup.complete", "lifespan.shutdown.complete"]
    assert closed


def test_paths_it_does_not_forward_reach_the_app() -> None:
    seen: list[str] = []

    async def app(scope: Scope, receive: Receive, send: Send) -> None:
        seen.append(scope["path"])
        await send({"type": "http.response.start", "status": 204, "headers": []})
        await send({"type": "http.response.body", "body": b""})

    async def run() -> int:
        transport = httpx.ASGITransport(app=WriterProxy(app, "http://127.0.0.1:9"))
        async with httpx.AsyncClient(transport=transport, base_url="http://reader") as client:
            return (await client.get("/kb/query", params={"pattern": "?s ?p ?o"})).status_code

    assert asyncio.run(run()) == 204
    assert seen == ["/kb/query"]


def test_an_unreachable_writer_is_a_503_in_the_error_shape() -> None:
    async def app(scope: Scope, receive: Receive, send: Send) -> None:
        raise AssertionError("a forwarded path must not reach the reader's app")

    async def run() -> httpx.Response:
        transport = httpx.ASGITransport(app=WriterProxy(app, "http://127.0.0.1:9"))
        async with httpx.AsyncClient(transport=transport, base_url="http://reader") as client:
            return await client.get("/scene")

    response = asyncio.run(run())
    assert response.status_code == 503
    assert response.json()["code"] == "writer_unavailable"
