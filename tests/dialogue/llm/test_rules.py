import asyncio
import json

from dialogue.llm.base import ChatModel, ChatRequest, TurnContext
from dialogue.llm.rules import RulesModel
from dialogue.reference.grounding import build_snapshot
from dialogue.schema import parse_answer
from kb import KB


def test_rules_model_answers_through_the_protocol_in_the_llm_json_shape(kitchen: KB) -> None:
    model = RulesModel()
    assert isinstance(model, ChatModel) and model.name == "rules"
    context = TurnContext("tell Tom that lunch is ready", "person_alice", build_snapshot(kitchen))
    result = asyncio.run(model.chat(ChatRequest((), {}, context), timeout=1))
    answer = parse_answer(result.content)
    assert answer.user_intent is not None
    assert answer.user_intent.type == "__intent_say__"
    assert answer.user_intent.input == "lunch is ready" and answer.user_intent.recipient == "person_tom"
    assert answer.user_intent.object is None
    assert set(json.loads(result.content)) == {"verbal_ack", "user_intent"}


def test_rules_model_says_when_it_did_not_understand(kitchen: KB) -> None:
    context = TurnContext("the moon is made of cheese", "person_alice", build_snapshot(kitchen))
    result = asyncio.run(RulesModel().chat(ChatRequest((), {}, context), timeout=1))
    assert not result.understood and parse_answer(result.content).user_intent is None


def test_a_compound_request_answers_every_intent_in_order(kitchen: KB) -> None:
    context = TurnContext("take the sponge and put it on the shelf", "person_alice", build_snapshot(kitchen))
    answer = parse_answer(asyncio.run(RulesModel().chat(ChatRequest((), {}, context), timeout=1)).content)
    assert answer.user_intents is not None
    assert [(w.type, w.object, w.recipient) for w in answer.user_intents] == [
        ("__intent_grab_object__", "sponge_1", None),
        ("__intent_place_object__", "sponge_1", "shelf_1"),
    ]
    assert answer.user_intent == answer.user_intents[0]


def test_the_rules_read_the_lexicon_the_engine_keeps(kitchen: KB) -> None:
    """Through the engine the rules use the engine's lexicon of each snapshot: no second copy of
    every entity's names. A context without one still works (the model makes its own)."""
    from dialogue.engine import DialogueEngine

    model = RulesModel()
    engine = DialogueEngine(kitchen, model)
    result = asyncio.run(engine.turn("give me the sponge", speaker="person_alice"))
    assert [i.data.get("object") for i in result.intents] == ["sponge_1"]
    assert model._lexicons is None
    alone = RulesModel().interpret(TurnContext("give me the sponge", "person_alice", build_snapshot(kitchen)))
    assert alone.understood
