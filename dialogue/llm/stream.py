"""Backends that can hand out their answer while they generate it.

`chat_stream` answers exactly as `chat` would (the same `ChatResult`, the same errors), and calls
`on_text` with each piece of the content as it is generated, in order, on the event loop. The
pieces joined are the content. A backend that cannot stream simply lacks the method: callers then
use `chat` and get the whole answer at once (see dialogue.earlyack).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol, runtime_checkable

from dialogue.llm.base import ChatRequest, ChatResult

TextSink = Callable[[str], None]


@runtime_checkable
class StreamingChatModel(Protocol):
    """A chat backend that also streams (`timeout` is the time left in the turn, in seconds)."""

    @property
    def name(self) -> str: ...

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult: ...

    async def chat_stream(self, request: ChatRequest, timeout: float, on_text: TextSink) -> ChatResult: ...
