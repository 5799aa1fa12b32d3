"""Hybrid: the offline rules first, another model only for what they do not understand.

A wrapper model (dialogue.llm.wrapper), like pydantic-ai's FallbackModel: it composes two backends
instead of a flag threaded through the engine. The engine asks it `prescreen` (the rules' answer, no
prompt built: as fast as the rules alone) and sends the turns it did not answer to `llm`, the inner
model. Used on its own, `chat` does both steps in order. Everything else (preloading, the doctor's
check, closing) is the inner model's.
"""

from __future__ import annotations

from dialogue.llm.base import ChatModel, ChatRequest, ChatResult, EarlyAnswer, TurnContext
from dialogue.llm.rules import RulesModel
from dialogue.llm.wrapper import WrapperModel


class HybridModel(WrapperModel):
    def __init__(self, inner: ChatModel, rules: RulesModel | None = None) -> None:
        if inner.llm is None:
            # Rules behind rules would only ever answer "not understood" twice.
            raise ValueError(f"hybrid needs a model that reads prompts behind the rules, not {inner.name!r}")
        super().__init__(inner)
        # A name read from a misspelt word is a guess: the model sees the words and the situation.
        self.rules = rules or RulesModel(take_guesses=False)

    @property
    def inner(self) -> ChatModel:
        """The model behind the rules."""
        return self.wrapped

    @property
    def name(self) -> str:
        return f"hybrid:{self.inner.name}"

    @property
    def llm(self) -> ChatModel | None:
        return self.inner.llm

    def prescreen(self, context: TurnContext) -> EarlyAnswer | None:
        return self.rules.prescreen(context)

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult:
        # A repair request follows the inner model's own invalid answer: it is the inner model's.
        if not request.repair:
            first = await self.rules.chat(request, timeout)
            if first.understood:
                return first
        return await self.inner.chat(request, timeout)
