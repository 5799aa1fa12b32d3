"""The dialogue manager tells its observers of every turn once it has its result."""

from __future__ import annotations

import asyncio

from dialogue.engine import DialogueEngine, EngineConfig
from dialogue.llm.testing import ScriptedModel
from dialogue.sessions.manager import DialogueManager
from dialogue.sessions.observers import TurnRecord
from kb import KB


def test_observers_see_each_turn_and_one_that_fails_changes_nothing(kitchen: KB) -> None:
    seen: list[TurnRecord] = []

    async def broken(record: TurnRecord) -> None:
        raise RuntimeError("observer bug")

    async def keep(record: TurnRecord) -> None:
        seen.append(record)

    manager = DialogueManager(DialogueEngine(kitchen), observers=[broken, keep])

    async def run() -> list[str]:
        dialogue = (await manager.start_async()).id
        first = await manager.interact("person_alice", "bring me the cookbook", dialogue_id=dialogue)
        second = await manager.interact("person_alice", "thanks", dialogue_id=dialogue)
        await manager.interact("person_alice", "noted", dialogue_id=dialogue, response_expected=False)
        return [first.response, second.response, dialogue]

    first, second, dialogue = asyncio.run(run())
    assert [(r.dialogue_id, r.user_id, r.text, r.result.response) for r in seen] == [
        (dialogue, "person_alice", "bring me the cookbook", first), (dialogue, "person_alice", "thanks", second)]
    assert [i.intent for i in seen[0].result.intents] == ["__intent_bring_object__"]


def test_a_turn_answered_late_is_observed_with_its_fallback(kitchen: KB) -> None:
    seen: list[TurnRecord] = []

    async def keep(record: TurnRecord) -> None:
        seen.append(record)

    model = ScriptedModel([{"verbal_ack": "ok", "user_intent": None}] * 2, delay=0.6)
    manager = DialogueManager(DialogueEngine(kitchen, model, EngineConfig(deadline=0.3)), observers=[keep])

    async def run() -> None:
        await asyncio.gather(manager.interact("person_alice", "hmm one"), manager.interact("person_alice", "hmm two"))

    asyncio.run(run())
    assert sorted(r.text for r in seen) == ["hmm one", "hmm two"]
    assert all(r.result.intents[0].intent == "__raw_user_input__" for r in seen)
