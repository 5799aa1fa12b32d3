"""One long-lived HTTP client per backend: made on first use, reused by every turn, closed once.

A client keeps its connections alive between turns (no TCP set-up per turn). httpx clients belong to
the event loop that opened their connections, so the client is tied to the loop it was made on. A
process normally has one loop (the service, `situated chat`, `situated eval`); a client whose loop
has ended (a script running `asyncio.run` per turn) cannot be closed any more and is replaced by a
new one. Two live loops sharing one backend is an error, not a silent second client.
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from contextlib import AbstractAsyncContextManager, AsyncExitStack
from typing import Any, Generic, TypeVar

from dialogue.llm.base import ModelError

C = TypeVar("C", bound=AbstractAsyncContextManager[Any])


class LoopClient(Generic[C]):
    """The client `factory` makes, for the running event loop. `made` counts the clients made."""

    def __init__(self, factory: Callable[[], C], what: str) -> None:
        self._factory = factory
        self._what = what
        self._client: C | None = None
        self._loop: asyncio.AbstractEventLoop | None = None
        self._exit = AsyncExitStack()
        self.made = 0

    @property
    def open(self) -> bool:
        return self._client is not None

    def get(self) -> C:
        """The client (made now if there is none for this loop). Call it from a coroutine."""
        loop = asyncio.get_running_loop()
        if self._client is not None and self._loop is not loop:
            if self._loop is not None and not self._loop.is_closed():
                raise ModelError(f"{self._what} is in use by another event loop; give each loop its model")
            self._client, self._exit = None, AsyncExitStack()  # its loop, and connections, are gone
        if self._client is None:
            client = self._factory()
            # Registered without entering it: httpx and ollama clients work unentered, and their
            # __aexit__ closes them (ollama's own close() is untyped).
            self._exit.push_async_exit(client)
            self._client, self._loop = client, loop
            self.made += 1
        return self._client

    async def aclose(self) -> None:
        """Close the client (on the loop that used it). The next `get` makes a new one."""
        exit_stack, self._exit = self._exit, AsyncExitStack()
        self._client = self._loop = None
        await exit_stack.aclose()
