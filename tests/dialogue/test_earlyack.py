"""The early ack: a streamed answer's verbal_ack as soon as its string closes, at most once per turn."""

from __future__ import annotations

import asyncio
import json

import pytest

from dialogue import intents as I
from dialogue.earlyack import AckDetector, acks_to, ask, read_ack
from dialogue.engine import DialogueEngine, EngineConfig
from dialogue.llm.testing import FunctionModel, ScriptedModel
from kb import KB
from tests.dialogue.llm.common import ANSWER, request

ALICE = "person_alice"


@pytest.mark.parametrize(("text", "expected"), [
    ("", (None, False)),
    ("  {", (None, False)),
    ('{"verbal_ack": "Hel', ("Hel", False)),
    ('{"verbal_ack": "Hello', ("Hello", False)),
    ('{"verbal_ack": "Hello"', ("Hello", True)),
    ('noise {"verbal_ack": "Hi \\"you\\"", "user', ('Hi "you"', True)),
    ('{"verbal_ack": nu', (None, False)),
    ('{"verbal_ack": null,', (None, True)),
    ('{"user_intent": {"ty', (None, True)),
    ('{"verbal_ack": 12,', (None, True)),
    ("{oops", (None, True)),
])
def test_read_ack(text: str, expected: tuple[str | None, bool]) -> None:
    assert read_ack(text) == expected


def feed(answer: str, size: int = 3) -> list[str]:
    acks: list[str] = []
    detector = AckDetector(acks.append)
    for start in range(0, len(answer), size):
        detector.feed(answer[start:start + size])
    return acks


def test_detector_reports_the_ack_once_when_its_string_closes() -> None:
    acks: list[str] = []
    detector = AckDetector(acks.append)
    detector.feed('{"verbal_ack": "  On my ')
    assert acks == []
    detector.feed('way."')
    assert acks == ["On my way."]  # trimmed like the reply
    detector.feed(', "user_intent": null}')
    assert acks == ["On my way."] and detector.done


@pytest.mark.parametrize("answer", [
    '{"verbal_ack": null, "user_intent": null}',
    '{"verbal_ack": "   ", "user_intent": null}',
    '{"user_intent": null, "verbal_ack": "late"}',
    "I think you want the cup",
])
def test_no_ack_from_an_answer_that_does_not_start_with_one(answer: str) -> None:
    assert feed(answer) == []


def test_ask_streams_only_while_a_sink_listens() -> None:
    model = ScriptedModel([ANSWER, ANSWER], chunk_size=5)
    acks: list[str] = []

    async def both() -> None:
        assert (await ask(model, request(), 1)).content == ANSWER  # nobody listens: plain chat
        with acks_to(acks.append):
            assert (await ask(model, request(), 1)).content == ANSWER

    asyncio.run(both())
    assert acks == ["OK"]


def test_a_backend_that_cannot_stream_answers_without_ack() -> None:
    model = FunctionModel(lambda r: ANSWER)
    acks: list[str] = []

    async def go() -> str:
        with acks_to(acks.append):
            return (await ask(model, request(), 1)).content

    assert asyncio.run(go()) == ANSWER and acks == []


def test_one_ack_per_turn_and_none_after_it(kitchen: KB) -> None:
    """The first answer is invalid (an object not in the KB) and its ack goes out; the repair's ack
    does not; the turn's reply is the repaired one."""
    bad = {"verbal_ack": "Taking the unicorn.", "user_intent": {"type": I.GRAB_OBJECT, "object": "unicorn"}}
    good = {"verbal_ack": "Taking the cup.", "user_intent": {"type": I.GRAB_OBJECT, "object": "cup_1"}}
    model = ScriptedModel([bad, good], chunk_size=2)
    engine = DialogueEngine(kitchen, model, EngineConfig(deadline=30))
    acks: list[str] = []

    async def go() -> str:
        with acks_to(acks.append):
            result = await engine.turn("grab it", speaker=ALICE)
        await ask(ScriptedModel([json.dumps(good)]), request(), 1)  # outside the turn: no sink
        return result.response

    assert asyncio.run(go()) == "Taking the cup."
    assert acks == ["Taking the unicorn."]


def test_concurrent_turns_keep_their_own_sinks(kitchen: KB) -> None:
    def answer(ack: str) -> dict[str, object]:
        return {"verbal_ack": ack, "user_intent": {"type": I.GRAB_OBJECT, "object": "cup_1"}}

    model = ScriptedModel([answer("first"), answer("second")], chunk_size=1, chunk_delay=0.001)
    engine = DialogueEngine(kitchen, model, EngineConfig(deadline=30))
    heard: dict[str, list[str]] = {"a": [], "b": []}

    async def one(name: str) -> None:
        with acks_to(heard[name].append):
            await engine.turn("grab it", speaker=ALICE)

    async def both() -> None:
        await asyncio.gather(one("a"), one("b"))

    asyncio.run(both())
    assert sorted(heard["a"] + heard["b"]) == ["first", "second"]
    assert len(heard["a"]) == len(heard["b"]) == 1
