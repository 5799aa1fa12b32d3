import asyncio

import httpx
import pytest

from dialogue.llm.base import ModelError
from dialogue.llm.connection import LoopClient


def clients() -> LoopClient[httpx.AsyncClient]:
    return LoopClient(httpx.AsyncClient, "test backend")


def test_one_client_per_loop_reused_until_closed() -> None:
    shared = clients()

    async def use() -> tuple[httpx.AsyncClient, httpx.AsyncClient]:
        first, second = shared.get(), shared.get()
        await shared.aclose()
        return first, second

    first, second = asyncio.run(use())
    assert first is second and shared.made == 1
    assert first.is_closed and not shared.open


def test_a_closed_client_is_made_again_on_next_use() -> None:
    shared = clients()

    async def twice() -> tuple[httpx.AsyncClient, httpx.AsyncClient]:
        first = shared.get()
        await shared.aclose()
        return first, shared.get()

    first, second = asyncio.run(twice())
    assert first is not second and first.is_closed and not second.is_closed and shared.made == 2


def test_a_client_whose_loop_ended_is_replaced() -> None:
    shared = clients()

    async def get() -> httpx.AsyncClient:
        return shared.get()

    first = asyncio.run(get())
    second = asyncio.run(get())
    assert first is not second and shared.made == 2


def test_a_client_in_use_by_another_live_loop_is_an_error() -> None:
    shared = clients()

    async def get() -> httpx.AsyncClient:
        return shared.get()

    loop = asyncio.new_event_loop()
    try:
        client = loop.run_until_complete(get())
        with pytest.raises(ModelError, match="in use by another event loop"):
            asyncio.run(get())
        loop.run_until_complete(shared.aclose())
        assert client.is_closed
    finally:
        loop.close()


def test_get_needs_a_running_loop() -> None:
    with pytest.raises(RuntimeError):
        clients().get()
