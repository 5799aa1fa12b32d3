"""The roles table: the default role is the engine's turn, the ask role a form; others are refused."""

from __future__ import annotations

import asyncio

import pytest

from dialogue.engine import DialogueEngine
from dialogue.roles import TOOK_LEAVE, BadConfiguration, DefaultRole, Roles, UnknownRole
from dialogue.sessions.rolestate import Progress
from dialogue.trace.record import TraceRecorder
from kb import KB


def test_roles_by_name(kitchen: KB) -> None:
    roles = Roles(DialogueEngine(kitchen))
    assert roles.names == ["__ask__", "__default__"]
    assert isinstance(roles.get("__default__"), DefaultRole)
    with pytest.raises(UnknownRole, match="unsupported dialogue role 'x'; supported: \\['__ask__', '__default__'\\]"):
        roles.get("x")
    assert roles.get("__default__").open("{}") == roles.get("__default__").open("") == ("", "")
    for bad, why in (("hello", "is not JSON"), ("[1, 2]", "must be a JSON object, not list")):
        with pytest.raises(BadConfiguration, match=f"the __default__ role's configuration {why}"):
            roles.get("__default__").open(bad)
    line, state = roles.get("__ask__").open('{"question": "Age?", "result_schema_properties": {"a": {"type": "integer"}}}')
    assert line == "Age?" and '"asked":"a"' in state


def test_the_default_role_is_the_engine_turn(kitchen: KB) -> None:
    role = Roles(DialogueEngine(kitchen)).get("__default__")

    async def run() -> tuple[object, str]:
        deadline = asyncio.get_running_loop().time() + 5
        return await role.turn("{}", "", "pick up the cup", speaker="person_alice", history=(), locale=None,
                               deadline=deadline, trace=TraceRecorder(dialogue_id="d"))

    result, state = asyncio.run(run())
    assert state == "" and result.intents[0].intent == "__intent_grab_object__"  # type: ignore[attr-defined]
    assert result.trace.dialogue_id == "d"  # type: ignore[attr-defined]


def test_the_default_role_has_no_answer_to_a_system_update(kitchen: KB) -> None:
    role = Roles(DialogueEngine(kitchen)).get("__default__")

    async def run() -> object:
        deadline = asyncio.get_running_loop().time() + 5
        result, _state = await role.turn("{}", "", "pick up the cup", speaker="__system__", history=(), locale=None,
                                         deadline=deadline, trace=TraceRecorder(dialogue_id="d"))
        return result

    result = asyncio.run(run())
    assert (result.response, result.intents, result.error_msg) == ("", (), "")  # type: ignore[attr-defined]
    assert result.trace.answered_by == "recorded"  # type: ignore[attr-defined]


def test_a_default_dialogue_is_over_once_the_person_took_leave(kitchen: KB) -> None:
    role = Roles(DialogueEngine(kitchen)).get("__default__")

    async def run(text: str) -> tuple[object, str]:
        deadline = asyncio.get_running_loop().time() + 5
        return await role.turn("{}", "", text, speaker="person_alice", history=(), locale=None,
                               deadline=deadline, trace=TraceRecorder(dialogue_id="d"))

    result, state = asyncio.run(run("goodbye"))
    assert result.dialogue_terminal is True  # type: ignore[attr-defined]
    assert state == TOOK_LEAVE and role.progress(state) == Progress("done")
    result, state = asyncio.run(run("pick up the cup"))  # speaking again opens it
    assert result.dialogue_terminal is None and role.progress(state) == Progress()  # type: ignore[attr-defined]
