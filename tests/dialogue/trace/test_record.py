"""The turn trace recorded by the engine: stages, the prompt and schema sent, raw answers, repair."""

from __future__ import annotations

import asyncio

from dialogue.engine import DialogueEngine, EngineConfig
from dialogue.llm.testing import ScriptedModel
from dialogue.trace.record import MAX_EXCHANGES, MAX_TEXT, TraceRecorder, clip
from kb import KB

GRAB = {"verbal_ack": "OK.", "user_intent": {"type": "__intent_grab_object__", "object": "cup_1",
                                             "recipient": None, "goal": None, "input": None}}


def test_a_model_turn_records_what_was_sent_and_the_repair(kitchen: KB) -> None:
    model = ScriptedModel(['{"verbal_ack": "OK.", "user_intent": {"type": "__intent_fly__"}}', GRAB])
    engine = DialogueEngine(kitchen, model)
    result = asyncio.run(engine.turn("yo, cup", speaker="person_alice"))
    trace = result.trace
    assert trace is not None and trace.answered_by == "model" and trace.backend == "scripted"
    first, repair = trace.exchanges
    assert first.messages[0].role == "system" and "yo, cup" in first.messages[-1].content
    assert first.json_schema == model.requests[0].schema and "__intent_fly__" in (first.raw_answer or "")
    assert first.error is not None and "__intent_fly__" in first.error
    assert repair.repair and repair.error is None and trace.repaired
    assert [i.intent for i in trace.intents] == ["__intent_grab_object__"]
    assert trace.validation_errors == [first.error]
    names = [s.name for s in trace.stages]
    assert names[0] == "ground" and names.count("model") == 2 and names[-1] == "total"
    assert trace.snapshot is not None and trace.snapshot.entities == len(engine.ground()[0].entities)
    assert "person_alice" in trace.snapshot.focus
    assert trace.model_dump(by_alias=True)["exchanges"][0]["schema"] == first.json_schema


def test_a_rules_turn_and_a_fallback(kitchen: KB) -> None:
    rules = asyncio.run(DialogueEngine(kitchen).turn("pick up the cup", speaker="person_alice")).trace
    assert rules is not None and rules.answered_by == "rules" and rules.exchanges == []
    assert [s.name for s in rules.stages] == ["ground", "rules", "total"]
    # The deadline leaves a loaded machine time to send the request; the model answers long after.
    slow = DialogueEngine(kitchen, ScriptedModel([GRAB], delay=60.0), EngineConfig(deadline=3.0))
    fallback = asyncio.run(slow.turn("yo", speaker="person_alice")).trace
    assert fallback is not None and fallback.answered_by == "fallback" and "deadline" in fallback.error_msg
    (asked,) = fallback.exchanges  # the request that was sent, with no answer
    assert asked.raw_answer is None and asked.messages


def test_bounded() -> None:
    assert clip("x" * (MAX_TEXT + 5)).endswith("… [5 more characters]")
    recorder = TraceRecorder(input="y" * (MAX_TEXT * 2))
    assert len(recorder.trace.input) < MAX_TEXT + 40
    for _ in range(MAX_EXCHANGES + 3):
        recorder.request("m", [("user", "hi")], {})
    for i in range(100):
        recorder.note(f"note {i}")
    trace = recorder.finish(response="", backend="m", answered_by="model")
    assert len(trace.exchanges) == MAX_EXCHANGES and len(trace.notes) < 100
