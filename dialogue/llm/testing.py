"""Test models: real backends whose answers come from a script or a Python function.

Shipped in the package (not only in tests) so that applications can test their wiring offline.
"""

from __future__ import annotations

import asyncio
import json
from collections import deque
from collections.abc import Awaitable, Callable, Iterable
from typing import Any

from dialogue.llm.base import ChatModel, ChatRequest, ChatResult, ModelError
from dialogue.llm.stream import TextSink

Answer = str | dict[str, Any] | ChatResult | BaseException


def _result(answer: Answer) -> ChatResult:
    if isinstance(answer, BaseException):
        raise answer
    if isinstance(answer, ChatResult):
        return answer
    if isinstance(answer, dict):
        return ChatResult(json.dumps(answer))
    return ChatResult(answer)


#: Requests a test model keeps (each holds its turn's snapshot: a long-running service kept them all).
KEPT = 100


def _keep(requests: list[ChatRequest], request: ChatRequest) -> None:
    requests.append(request)
    if len(requests) > KEPT:
        del requests[0]


class ScriptedModel(ChatModel):
    """Answers from a queue: a JSON string, a dict (dumped), a ChatResult, or an exception to raise.

    Every request is recorded in `requests` (the last `KEPT`: a benchmark's service answers
    thousands). `delay` seconds are slept before each answer (to test
    deadlines). An exhausted script is a ModelError, never a silent default answer.

    It also streams (dialogue.llm.stream): `chat_stream` hands out the answer in pieces of
    `chunk_size` characters, `chunk_delay` seconds apart (the first after `delay`).
    """

    def __init__(
        self,
        answers: Iterable[Answer] = (),
        *,
        delay: float = 0.0,
        name: str = "scripted",
        chunk_size: int = 4,
        chunk_delay: float = 0.0,
    ) -> None:
        if chunk_size < 1 or chunk_delay < 0 or delay < 0:
            raise ValueError("chunk_size must be >= 1, delay and chunk_delay >= 0")
        self._answers: deque[Answer] = deque(answers)
        self.delay = delay
        self.chunk_size = chunk_size
        self.chunk_delay = chunk_delay
        self._name = name
        self.requests: list[ChatRequest] = []

    @property
    def name(self) -> str:
        return self._name

    def push(self, *answers: Answer) -> None:
        self._answers.extend(answers)

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult:
        _keep(self.requests, request)
        if self.delay:
            await asyncio.sleep(self.delay)
        if not self._answers:
            raise ModelError("scripted model has no answer left")
        return _result(self._answers.popleft())

    async def chat_stream(self, request: ChatRequest, timeout: float, on_text: TextSink) -> ChatResult:
        result = await self.chat(request, timeout)
        for start in range(0, len(result.content), self.chunk_size):
            if start and self.chunk_delay:
                await asyncio.sleep(self.chunk_delay)
            on_text(result.content[start : start + self.chunk_size])
        return result


Responder = Callable[[ChatRequest], Answer | Awaitable[Answer]]


class FunctionModel(ChatModel):
    """Answers computed by a Python callable (sync or async) from the request."""

    def __init__(self, function: Responder, *, name: str = "function") -> None:
        self.function = function
        self._name = name
        self.requests: list[ChatRequest] = []  # (the last `KEPT`: see ScriptedModel)

    @property
    def name(self) -> str:
        return self._name

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult:
        _keep(self.requests, request)
        answer = self.function(request)
        if isinstance(answer, Awaitable):
            answer = await answer
        return _result(answer)
