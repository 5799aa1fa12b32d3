import asyncio

import pytest

from dialogue import intents as I
from dialogue.engine import DialogueEngine
from dialogue.history import ASSISTANT_USER_ID, SYSTEM_USER_ID, Utterance
from dialogue.llm.testing import ScriptedModel
from dialogue.sessions import DEFAULT_DIALOGUE, DialogueError, DialogueManager
from kb import KB, KbError


def test_default_dialogue_always_exists(kitchen: KB) -> None:
    manager = DialogueManager(DialogueEngine(kitchen))
    assert manager.ids() == [DEFAULT_DIALOGUE]
    result = asyncio.run(manager.interact("person_alice", "pick up the cup"))
    assert result.intents[0].data == {"object": "cup_1"}
    manager.end(DEFAULT_DIALOGUE)
    assert manager.ids() == [DEFAULT_DIALOGUE] and len(manager.get(DEFAULT_DIALOGUE).history) == 0


def test_dialogues_are_separate_and_roles_recorded(kitchen: KB) -> None:
    manager = DialogueManager(DialogueEngine(kitchen))
    a = manager.start(locale="en_GB")
    b = manager.start()
    assert a.id != b.id and a.role == "__default__"
    asyncio.run(manager.interact("person_alice", "hello", dialogue_id=a.id))
    asyncio.run(manager.interact(SYSTEM_USER_ID, "Tom arrived", dialogue_id=a.id, response_expected=False))
    said = asyncio.run(
        manager.interact(ASSISTANT_USER_ID, "I am here", dialogue_id=a.id, response_expected=False)
    )
    assert said.response == "" and said.intents == ()
    roles = [(u.role, u.text) for u in manager.get(a.id).history]
    assert roles == [
        ("user", "hello"),
        ("assistant", "Hello Alice!"),
        ("system", "Tom arrived"),
        ("assistant", "I am here"),
    ]
    assert len(manager.get(b.id).history) == 0


def test_locale_of_the_dialogue_reaches_raw_input(kitchen: KB) -> None:
    manager = DialogueManager(DialogueEngine(kitchen))
    d = manager.start(locale="fr_FR")
    result = asyncio.run(manager.interact("p", "bla bla", dialogue_id=d.id))
    assert result.intents[0].intent == I.RAW_USER_INPUT and result.intents[0].data["locale"] == "fr_FR"


def test_clarification_is_completed_within_a_live_dialogue(cups: KB) -> None:
    manager = DialogueManager(DialogueEngine(cups))
    d = manager.start()
    first = asyncio.run(manager.interact("person_nina", "pick up the cup", dialogue_id=d.id))
    assert first.intents == () and first.response.endswith("?")
    second = asyncio.run(manager.interact("person_nina", "the red one", dialogue_id=d.id))
    assert second.intents[0].data == {"object": "cup_red"}


def test_many_dialogues_concurrently(kitchen: KB) -> None:
    manager = DialogueManager(DialogueEngine(kitchen))
    ids = [manager.start().id for _ in range(20)]

    async def all_turns() -> list[str]:
        results = await asyncio.gather(
            *(manager.interact("person_alice", "grab the apple", dialogue_id=i) for i in ids)
        )
        return [r.intents[0].data["object"] for r in results]

    assert asyncio.run(all_turns()) == ["apple_1"] * 20
    assert all(len(manager.get(i).history) == 2 for i in ids)


def test_stateless_history_replaces_the_stored_one(cups: KB) -> None:
    manager = DialogueManager(DialogueEngine(cups))
    history = [
        Utterance("person_nina", "grab the cup"),
        Utterance(ASSISTANT_USER_ID, "Which cup do you mean?"),
    ]
    result = asyncio.run(manager.interact("person_nina", "the blue one", history=history))
    assert result.intents[0].data == {"object": "cup_blue"}


def test_errors_and_bounds(kitchen: KB) -> None:
    manager = DialogueManager(DialogueEngine(kitchen, ScriptedModel()), max_dialogues=3, max_turns=4)
    with pytest.raises(DialogueError, match="unknown dialogue 'nope'"):
        manager.get("nope")
    with pytest.raises(DialogueError, match="unsupported dialogue role"):
        manager.start(role="__ask__")
    first = manager.start(dialogue_id="one").id
    with pytest.raises(DialogueError, match="already exists"):
        manager.start(dialogue_id="one")
    manager.start()
    manager.start()
    assert first not in manager.ids() and DEFAULT_DIALOGUE in manager.ids() and len(manager.ids()) == 3
    with pytest.raises(DialogueError, match="user_id is required"):
        asyncio.run(manager.interact("", "hi"))
    for _ in range(5):
        asyncio.run(manager.interact("p", "hi", response_expected=False))
    assert len(manager.get(DEFAULT_DIALOGUE).history) == 4


def test_a_turn_holding_a_lone_surrogate_is_refused_and_not_recorded(kitchen: KB) -> None:
    manager = DialogueManager(DialogueEngine(kitchen))
    for user_id, text, history in [("person_alice", "\ud800 cup", None), ("person\udc00", "hi", None),
                                   ("person_alice", "hi", [Utterance("person_alice", "x\ud800")])]:
        with pytest.raises(DialogueError, match="not valid Unicode"):
            asyncio.run(manager.interact(user_id, text, history=history))
        with pytest.raises(DialogueError, match="not valid Unicode"):
            asyncio.run(manager.interact(user_id, text, history=history, response_expected=False))
    assert len(manager.get(DEFAULT_DIALOGUE).history) == 0
    with pytest.raises(KbError, match="the utterance is not valid Unicode"):
        asyncio.run(manager.engine.turn("\udc00 cup", speaker="person_alice"))
