import asyncio
from typing import Any

import pytest

from dialogue import intents as I
from dialogue.ask import AskError
from dialogue.engine import NO_ANSWER_IN_TIME, DialogueEngine, EngineConfig, TurnResult, sorry
from dialogue.history import ASSISTANT_USER_ID, SYSTEM_USER_ID, Utterance
from dialogue.llm.base import ChatRequest
from dialogue.llm.testing import FunctionModel, ScriptedModel
from dialogue.roles import UnknownRole
from dialogue.sessions.manager import (
    DEFAULT_DIALOGUE,
    DialogueExists,
    DialogueManager,
    SessionError,
    UnknownDialogue,
)
from dialogue.sessions.rolestate import Progress
from kb import KB, KbError

SORRY = sorry()  # what the engine says when no answer comes in time


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
    with pytest.raises(SessionError, match="unknown dialogue 'nope'"):
        manager.get("nope")
    with pytest.raises(UnknownRole, match="unsupported dialogue role '__nope__'"):
        manager.start(role="__nope__")
    with pytest.raises(AskError, match="the ask role needs a question"):
        manager.start(role="__ask__")
    first = manager.start(dialogue_id="one").id
    with pytest.raises(DialogueExists, match="already exists: end it first, or choose another id"):
        manager.start(dialogue_id="one")
    manager.start()
    manager.start()
    assert first not in manager.ids() and DEFAULT_DIALOGUE in manager.ids() and len(manager.ids()) == 3
    with pytest.raises(SessionError, match="user_id is required"):
        asyncio.run(manager.interact("", "hi"))
    for _ in range(5):
        asyncio.run(manager.interact("p", "hi", response_expected=False))
    assert len(manager.get(DEFAULT_DIALOGUE).history) == 4


def test_a_turn_holding_a_lone_surrogate_is_refused_and_not_recorded(kitchen: KB) -> None:
    manager = DialogueManager(DialogueEngine(kitchen))
    for user_id, text, history in [("person_alice", "\ud800 cup", None), ("person\udc00", "hi", None),
                                   ("person_alice", "hi", [Utterance("person_alice", "x\ud800")])]:
        with pytest.raises(SessionError, match="not valid Unicode"):
            asyncio.run(manager.interact(user_id, text, history=history))
        with pytest.raises(SessionError, match="not valid Unicode"):
            asyncio.run(manager.interact(user_id, text, history=history, response_expected=False))
    assert len(manager.get(DEFAULT_DIALOGUE).history) == 0
    with pytest.raises(KbError, match="the utterance is not valid Unicode"):
        asyncio.run(manager.engine.turn("\udc00 cup", speaker="person_alice"))
def test_each_queued_turn_answers_within_its_own_deadline_and_in_order(kitchen: KB) -> None:
    """Turns of one dialogue run one at a time, yet none waits past its own deadline for the ones
    before it: with a model that never answers, twelve turns sent at once all answer (politely,
    with the raw input) within one deadline of their arrival, and the history keeps their order."""
    deadline, margin = 1.0, 4.0  # 12 turns one after the other would take 12 s

    async def hang(request: ChatRequest) -> str:
        await asyncio.sleep(3600)
        raise AssertionError("the hanging model answered")

    engine = DialogueEngine(kitchen, FunctionModel(hang, name="hanging"), EngineConfig(deadline=deadline))
    manager = DialogueManager(engine, max_turns=40)
    texts = [f"fetch the thing number {n}" for n in range(12)]

    async def timed(text: str) -> tuple[TurnResult, float]:
        loop = asyncio.get_running_loop()
        arrived = loop.time()
        result = await manager.interact("person_alice", text)
        return result, loop.time() - arrived

    async def scenario() -> list[tuple[TurnResult, float]]:
        answers = await asyncio.gather(*(timed(text) for text in texts))
        # A later turn is queued behind every earlier one, so it sees all of them recorded.
        await manager.interact("person_alice", "that is all", response_expected=False)
        return answers

    answers = asyncio.run(scenario())
    for text, (result, elapsed) in zip(texts, answers, strict=True):
        assert elapsed < deadline + margin, f"{text!r} answered after {elapsed:.2f} s"
        assert result.response == SORRY and "deadline" in result.error_msg
        (raw,) = result.intents
        assert raw.intent == I.RAW_USER_INPUT and raw.data["input"] == text
    history = manager.get(DEFAULT_DIALOGUE).history
    assert [u.text for u in history if u.speaker == "person_alice"] == [*texts, "that is all"]
    assert [u.text for u in history if u.speaker == ASSISTANT_USER_ID] == [SORRY] * len(texts)


def test_a_queued_turn_still_gets_the_time_left_of_its_deadline(kitchen: KB) -> None:
    """A turn that waited for the one before it is answered by the model when it is its turn
    and its own deadline has not passed."""
    calls = 0

    async def slow_first(request: ChatRequest) -> dict[str, Any]:
        nonlocal calls
        calls += 1
        if calls == 1:
            await asyncio.sleep(3600)
        return {"verbal_ack": "OK.", "user_intent": {"type": I.GRAB_OBJECT, "object": "cup_1"}}

    engine = DialogueEngine(kitchen, FunctionModel(slow_first), EngineConfig(deadline=2.0))
    manager = DialogueManager(engine)

    async def scenario() -> tuple[TurnResult, TurnResult]:
        first = asyncio.ensure_future(manager.interact("person_alice", "grab it"))
        await asyncio.sleep(1.0)  # the first turn gives up at 2 s; the second's deadline is at 3 s
        second = await manager.interact("person_alice", "grab the cup")
        return await first, second

    first, second = asyncio.run(scenario())
    assert [i.intent for i in first.intents] == [I.RAW_USER_INPUT]
    assert second.intents[0].data == {"object": "cup_1"} and second.error_msg == ""


def test_a_person_who_says_nothing_gets_no_answer_and_nothing_is_recorded(kitchen: KB) -> None:
    """chatbot_msgs allows an empty input: not an error, nothing said, nothing to answer or keep."""
    manager = DialogueManager(DialogueEngine(kitchen))
    for text in ("", "   ", "\n\t"):
        for expected in (True, False):
            result = asyncio.run(manager.interact("person_alice", text, response_expected=expected))
            assert (result.response, result.intents, result.error_msg) == ("", (), "")
    assert manager.get(DEFAULT_DIALOGUE).history == ()
    with pytest.raises(SessionError, match="unknown dialogue 'nope'"):  # still a turn of a dialogue
        asyncio.run(manager.interact("person_alice", "", dialogue_id="nope"))


def test_system_updates_and_the_robots_own_words_are_recorded_never_misunderstood(kitchen: KB) -> None:
    manager = DialogueManager(DialogueEngine(kitchen))
    d = manager.start()
    update = asyncio.run(manager.interact(SYSTEM_USER_ID, '{"intent": "__intent_greet__", "data": {}}',
                                          dialogue_id=d.id))
    own = asyncio.run(manager.interact(ASSISTANT_USER_ID, "I will fetch it.", dialogue_id=d.id))
    empty = asyncio.run(manager.interact(SYSTEM_USER_ID, "", dialogue_id=d.id))
    for result in (update, own, empty):
        assert (result.response, result.intents, result.error_msg) == ("", (), "")
    assert [(u.role, u.text) for u in manager.get(d.id).history] == [
        ("system", '{"intent": "__intent_greet__", "data": {}}'), ("assistant", "I will fetch it.")]


def test_an_empty_system_update_asks_an_ask_dialogue_its_question(kitchen: KB) -> None:
    """How a dialogue manager has the robot speak first: a system update, nothing said."""
    manager = DialogueManager(DialogueEngine(kitchen))
    config = '{"question": "How old are you?", "result_schema_properties": {"age": {"type": "integer"}}}'
    d = manager.start("__ask__", configuration=config)
    prompted = asyncio.run(manager.interact(SYSTEM_USER_ID, "", dialogue_id=d.id))
    assert prompted.response == "How old are you?" and prompted.intents == () and not prompted.dialogue_terminal


def test_a_turn_answers_within_its_own_timeout(kitchen: KB) -> None:
    async def slow(request: ChatRequest) -> dict[str, Any]:
        await asyncio.sleep(5)
        return {"verbal_ack": "late", "user_intent": None}

    manager = DialogueManager(DialogueEngine(kitchen, FunctionModel(slow), EngineConfig(deadline=30)))

    # The model answers after 5 s, the engine's deadline is 30 s: only the turn's timeout falls back.
    result = asyncio.run(manager.interact("person_alice", "blorp the glorp", timeout=0.3))
    assert result.response == SORRY and result.error_msg == NO_ANSWER_IN_TIME


def test_observers_hear_stateless_turns_and_observers_added_later(kitchen: KB) -> None:
    heard: list[tuple[str, str]] = []

    async def first(record: Any) -> None:
        heard.append(("first", record.dialogue_id))

    async def later(record: Any) -> None:
        heard.append(("later", record.dialogue_id))

    manager = DialogueManager(DialogueEngine(kitchen), observers=[first])
    asyncio.run(manager.interact("person_alice", "pick up the cup", dialogue_id="dm-1", role="__default__"))
    manager.add_observer(later)
    asyncio.run(manager.interact("person_alice", "pick up the cup"))
    asyncio.run(manager.interact("person_alice", "noted", response_expected=False))  # not answered: not told
    assert heard == [("first", "dm-1"), ("first", DEFAULT_DIALOGUE), ("later", DEFAULT_DIALOGUE)]


def test_progress_says_whether_a_dialogue_is_over_and_with_what(kitchen: KB) -> None:
    manager = DialogueManager(DialogueEngine(kitchen))
    config = '{"question": "How old are you?", "result_schema_properties": {"age": {"type": "integer"}}}'
    default, asked, cancelled = manager.start(), manager.start("__ask__", configuration=config), \
        manager.start("__ask__", configuration=config)
    asyncio.run(manager.interact("person_alice", "I am 40", dialogue_id=asked.id))
    asyncio.run(manager.interact("person_alice", "never mind", dialogue_id=cancelled.id))
    assert manager.progress(manager.get(default.id)) == Progress("open", "{}")
    assert manager.progress(manager.get(asked.id)) == Progress("done", '{"age": 40}')
    assert manager.progress(manager.get(cancelled.id)) == Progress("cancelled", "{}")


def test_ending_a_dialogue_says_where_its_role_was(kitchen: KB) -> None:
    manager = DialogueManager(DialogueEngine(kitchen))
    config = ('{"question": "Your age and name?", "result_schema_properties": {"age": {"type": "integer"}, '
              '"name": {"type": "string"}}}')
    asked, filled = manager.start("__ask__", configuration=config), manager.start("__ask__", configuration=config)
    asyncio.run(manager.interact("person_alice", "I am 40", dialogue_id=asked.id))
    asyncio.run(manager.interact("person_alice", "I am 40 and my name is Alice", dialogue_id=filled.id))
    assert manager.end(asked.id) == Progress("open", '{"age": 40}')  # ended before the form was filled
    assert manager.end(filled.id) == Progress("done", '{"age": 40, "name": "Alice"}')
    assert manager.end(DEFAULT_DIALOGUE) == Progress()
    with pytest.raises(UnknownDialogue):
        manager.end(asked.id)


def test_a_turn_cancelled_while_it_waits_leaves_the_queue_working(kitchen: KB) -> None:
    """A client that goes away while its turn waits (the HTTP request is cancelled) must not hold
    the dialogue: the turns after it run, and its words are not recorded."""
    calls = 0

    async def slow_first(request: ChatRequest) -> dict[str, Any]:
        nonlocal calls
        calls += 1
        if calls == 1:
            await asyncio.sleep(3600)
        return {"verbal_ack": "OK.", "user_intent": {"type": I.GRAB_OBJECT, "object": "cup_1"}}

    manager = DialogueManager(DialogueEngine(kitchen, FunctionModel(slow_first), EngineConfig(deadline=1.0)))

    async def scenario() -> TurnResult:
        first = asyncio.ensure_future(manager.interact("person_alice", "grab it"))
        await asyncio.sleep(0)
        gone = asyncio.ensure_future(manager.interact("person_alice", "never mind"))
        await asyncio.sleep(0.1)
        gone.cancel()
        await first
        return await manager.interact("person_alice", "grab the cup")

    last = asyncio.run(scenario())
    assert last.intents[0].data == {"object": "cup_1"}
    said = [u.text for u in manager.get(DEFAULT_DIALOGUE).history if u.speaker == "person_alice"]
    assert said == ["grab it", "grab the cup"]


def test_a_summary_is_given_to_the_turn_and_the_stored_history_is_kept(kitchen: KB) -> None:
    """`summary` (of earlier sessions) comes before the history the turn sees; in the 3.0 shape the
    stored history stays the dialogue's (it was replaced by the summary alone), and it is not stored."""
    model = ScriptedModel([{"verbal_ack": "Hello again.", "user_intent": None}] * 2)
    manager = DialogueManager(DialogueEngine(kitchen, model))
    d = manager.start()
    asyncio.run(manager.interact(SYSTEM_USER_ID, "Alice came in", dialogue_id=d.id, response_expected=False))
    asyncio.run(manager.interact("person_alice", "hi there", dialogue_id=d.id, summary="Alice likes tea."))
    seen = [(m.role, m.content) for m in model.requests[0].messages[1:-1]]
    assert seen == [("system", "Summary of earlier conversations: Alice likes tea."), ("system", "Alice came in")]
    assert [u.text for u in manager.get(d.id).history] == ["Alice came in", "hi there", "Hello again."]
    history = [Utterance(SYSTEM_USER_ID, "Bob left")]  # the 4.0 shape: the same order
    asyncio.run(manager.interact("person_alice", "hi", dialogue_id="dm", history=history, role="__default__",
                                 summary="Alice likes tea."))
    assert [m.content for m in model.requests[1].messages[1:-1]] == [
        "Summary of earlier conversations: Alice likes tea.", "Bob left"]
