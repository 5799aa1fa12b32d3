import asyncio

from dialogue.llm.base import ChatModel, ChatRequest, ChatResult, SelfCheck
from dialogue.llm.hybrid import HybridModel
from dialogue.llm.rules import RulesModel
from dialogue.llm.wrapper import WrapperModel
from kb import KB
from tests.dialogue.llm.test_hybrid import Recording, request


class Counting(WrapperModel):
    """A wrapper that only counts the requests it passes on."""

    def __init__(self, wrapped: ChatModel) -> None:
        super().__init__(wrapped)
        self.passed = 0

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult:
        self.passed += 1
        return await super().chat(request, timeout)


def test_what_a_wrapper_does_not_define_is_the_wrapped_models(kitchen: KB) -> None:
    inner = Recording({"verbal_ack": "Hi.", "user_intent": None})
    model = Counting(inner)
    assert isinstance(model, ChatModel) and model.name == "inner" and model.setup_hint == "start the inner server"
    assert asyncio.run(model.self_check(1.0)) == SelfCheck(True, "inner is fine")
    asyncio.run(model.preload())
    asyncio.run(model.aclose())
    assert inner.calls == ["self_check", "preload", "aclose"]
    result = asyncio.run(model.chat(request(kitchen, "hello"), 1.0))
    assert result.content == '{"verbal_ack": "Hi.", "user_intent": null}' and model.passed == 1
    assert len(inner.requests) == 1


def test_a_wrapper_reads_the_prompts_itself_when_its_model_reads_any() -> None:
    assert Counting(Recording()).llm is not None
    wrapped = Counting(Recording())
    assert wrapped.llm is wrapped  # requests go through the wrapper
    assert Counting(RulesModel()).llm is None  # nothing behind it reads prompts


def test_the_hybrid_is_a_wrapper_whose_prompts_are_its_inner_models() -> None:
    inner = Recording()
    model = HybridModel(inner)
    assert isinstance(model, WrapperModel) and model.wrapped is inner and model.llm is inner
