import asyncio
import json
from typing import Any

import pytest

from dialogue import intents as I
from dialogue.engine import DialogueEngine, TurnResult
from dialogue.llm.base import ChatMessage, ChatModel, ChatRequest, ModelError, SelfCheck, TurnContext
from dialogue.llm.hybrid import HybridModel
from dialogue.llm.rules import RulesModel
from dialogue.llm.testing import ScriptedModel
from dialogue.reference.grounding import build_snapshot
from dialogue.schema import parse_answer
from kb import KB

ALICE = "person_alice"
SUNNY = {"verbal_ack": "It is sunny.", "user_intent": None}


class Recording(ScriptedModel):
    """A scripted LLM that also records what is asked of it besides chat."""

    def __init__(self, *answers: Any) -> None:
        super().__init__(answers, name="inner")
        self.calls: list[str] = []

    @property
    def setup_hint(self) -> str:
        return "start the inner server"

    async def self_check(self, timeout: float) -> SelfCheck:
        self.calls.append("self_check")
        return SelfCheck(True, "inner is fine")

    async def preload(self) -> None:
        self.calls.append("preload")

    async def aclose(self) -> None:
        self.calls.append("aclose")


def request(kb: KB, text: str, repair: bool = False) -> ChatRequest:
    context = TurnContext(text, ALICE, build_snapshot(kb))
    return ChatRequest((ChatMessage("user", text),), {}, context, repair=repair)


def turn(engine: DialogueEngine, text: str) -> TurnResult:
    return asyncio.run(engine.turn(text, speaker=ALICE))


def test_prescreen_is_the_rules_answer_and_the_llm_is_the_inner_model(kitchen: KB) -> None:
    inner = Recording()
    model = HybridModel(inner)
    assert isinstance(model, ChatModel) and model.name == "hybrid:inner" and model.llm is inner
    early = model.prescreen(TurnContext("pick up the apple", ALICE, build_snapshot(kitchen)))
    assert early is not None and early.backend == "rules"
    assert early.answer.user_intent is not None and early.answer.user_intent.object == "apple_1"
    declined = model.prescreen(TurnContext("how is the weather today?", ALICE, build_snapshot(kitchen)))
    assert declined is not None and not declined.understood  # only why not: the inner model reads it
    assert inner.requests == []


def test_chat_alone_asks_the_rules_first_then_the_inner_model(kitchen: KB) -> None:
    inner = Recording(SUNNY, SUNNY)
    model = HybridModel(inner)
    first = asyncio.run(model.chat(request(kitchen, "pick up the apple"), timeout=5))
    answer = parse_answer(first.content)
    assert answer.user_intent is not None and answer.user_intent.object == "apple_1"
    assert inner.requests == []  # understood by the rules: the inner model was not asked
    second = asyncio.run(model.chat(request(kitchen, "how is the weather today?"), timeout=5))
    assert json.loads(second.content) == SUNNY and len(inner.requests) == 1
    # A repair request follows the inner model's own invalid answer: the rules are not asked again.
    repair = asyncio.run(model.chat(request(kitchen, "pick up the apple", repair=True), timeout=5))
    assert json.loads(repair.content) == SUNNY and len(inner.requests) == 2


def test_everything_else_is_the_inner_models() -> None:
    inner = Recording()
    model = HybridModel(inner)
    assert model.setup_hint == "start the inner server"
    assert asyncio.run(model.self_check(1.0)) == SelfCheck(True, "inner is fine")
    asyncio.run(model.preload())
    asyncio.run(model.aclose())
    assert inner.calls == ["self_check", "preload", "aclose"]


def test_the_rules_cannot_stand_behind_the_rules() -> None:
    with pytest.raises(ValueError, match="hybrid needs a model that reads prompts"):
        HybridModel(RulesModel())


def test_engine_answers_from_the_rules_without_asking_the_model(kitchen: KB) -> None:
    inner = Recording(SUNNY)
    engine = DialogueEngine(kitchen, HybridModel(inner))
    result = turn(engine, "pick up the apple")
    assert result.backend == "rules" and result.intents[0].data == {"object": "apple_1"}
    assert inner.requests == []
    weather = turn(engine, "how is the weather today?")
    assert weather.backend == "inner" and weather.response == "It is sunny." and weather.intents == ()
    (asked,) = inner.requests
    assert asked.context.text == "how is the weather today?" and asked.messages  # a real prompt


def test_engine_falls_back_when_the_model_behind_the_rules_is_down(kitchen: KB) -> None:
    engine = DialogueEngine(kitchen, HybridModel(ScriptedModel([ModelError("connection refused")])))
    assert turn(engine, "pick up the apple").backend == "rules"  # the rules need no server
    result = turn(engine, "how is the weather today?")
    assert result.backend == "fallback" and "connection refused" in result.error_msg


def test_the_rules_fast_path_builds_no_prompt(kitchen: KB, monkeypatch: pytest.MonkeyPatch) -> None:
    engine = DialogueEngine(kitchen, HybridModel(Recording(SUNNY)))
    built: list[str] = []
    messages = engine.prompts.messages

    def counted(context: TurnContext) -> tuple[ChatMessage, ...]:
        built.append(context.text)
        return messages(context)

    monkeypatch.setattr(engine.prompts, "messages", counted)
    assert turn(engine, "pick up the apple").backend == "rules" and built == []
    assert turn(engine, "how is the weather today?").backend == "inner"
    assert built == ["how is the weather today?"]


def test_a_name_read_from_a_typo_is_left_to_the_model_behind_the_rules(kitchen: KB) -> None:
    # The rules alone take their best reading ("cookbok": the cookbook), less sure; in hybrid mode
    # that guess goes to the model, which sees the words and the situation. A typo of a grammar word
    # ("plase") changes no referent: the rules keep it.
    alone = RulesModel().prescreen(TurnContext("pick up the cookbok", ALICE, build_snapshot(kitchen)))
    assert alone is not None and alone.answer.user_intent is not None
    assert alone.answer.user_intent.object == "book_1" and alone.answer.user_intent.confidence < 0.9
    inner = Recording(SUNNY)
    engine = DialogueEngine(kitchen, HybridModel(inner))
    assert turn(engine, "pick up the cookbok").backend == "inner" and len(inner.requests) == 1
    kept = turn(engine, "plase pick up the cookbook")
    assert kept.backend == "rules" and kept.intents[0].data == {"object": "book_1"}
    assert kept.intents[0].confidence < 0.9


def test_a_reading_the_rules_would_only_propose_goes_to_the_model_behind_them(kitchen: KB) -> None:
    # Alone, the rules ask ("Shall I dance?") and act on nothing; behind them, the model reads it.
    alone = RulesModel().prescreen(TurnContext("can you dance?", ALICE, build_snapshot(kitchen)))
    assert alone is not None and alone.confirm and alone.clarify and alone.answer.user_intent is None
    assert alone.answer.verbal_ack == "Shall I dance?"
    inner = Recording(SUNNY)
    engine = DialogueEngine(kitchen, HybridModel(inner))
    assert turn(engine, "can you dance?").backend == "inner" and len(inner.requests) == 1


def test_a_word_the_rules_do_not_know_goes_to_the_model_not_to_i_dont_see_any(kitchen: KB) -> None:
    # "bring me the glorp": the rules cannot tell a thing the scene lacks from a word they do not know
    alone = DialogueEngine(kitchen, RulesModel())
    said = turn(alone, "bring me the glorp")
    # alone, they say why they did not understand, and act on nothing (the raw input is passed on)
    assert not said.understood and said.response == "Sorry, I don't see any glorp."
    assert [i.intent for i in said.intents] == [I.RAW_USER_INPUT]
    inner = Recording(SUNNY, SUNNY)
    engine = DialogueEngine(kitchen, HybridModel(inner))
    assert turn(engine, "bring me the glorp").backend == "inner" and len(inner.requests) == 1
    # nor can they tell a thing called otherwise ("bunny" of a toy rabbit) from one not here
    assert turn(engine, "bring me the hammer").backend == "inner" and len(inner.requests) == 2
    # words the KB names, nothing here fitting them all: the rules answer themselves
    absent = turn(engine, "bring me the cup on the shelf")
    assert absent.backend == "rules" and absent.response == "Sorry, I don't see any cup on the shelf."
