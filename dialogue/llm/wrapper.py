"""A model composed around another, as pydantic-ai's `WrapperModel`: every member of the protocol a
wrapper does not define itself is the wrapped model's.

A wrapper reads prompts when anything behind it does, and then reads them itself (the requests go
through it, to the wrapped model): `llm` is the wrapper, unless it says otherwise (the hybrid sends
what its rules did not answer to the model behind them).
"""

from __future__ import annotations

from typing import Any

from dialogue.llm.base import ChatModel, ChatRequest, ChatResult, EarlyAnswer, SelfCheck, TurnContext


class WrapperModel(ChatModel):
    def __init__(self, wrapped: ChatModel) -> None:
        self.wrapped = wrapped

    @property
    def name(self) -> str:
        return self.wrapped.name

    @property
    def llm(self) -> ChatModel | None:
        return self if self.wrapped.llm is not None else None

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult:
        return await self.wrapped.chat(request, timeout)

    def prescreen(self, context: TurnContext) -> EarlyAnswer | None:
        return self.wrapped.prescreen(context)

    @property
    def setup_hint(self) -> str:
        return self.wrapped.setup_hint

    async def self_check(self, timeout: float) -> SelfCheck | None:
        return await self.wrapped.self_check(timeout)

    async def probe(self, timeout: float) -> dict[str, Any]:
        return await self.wrapped.probe(timeout)

    async def preload(self) -> None:
        await self.wrapped.preload()

    async def aclose(self) -> None:
        await self.wrapped.aclose()
