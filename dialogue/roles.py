"""Dialogue roles (chatbot_msgs `DialogueRole`): what a dialogue does with each turn, by role name.

`__default__` is the engine's turn (understand, ground, answer with intents); `__ask__` fills a form
(dialogue.ask). Each role opens a dialogue (an opening line, a first state) and runs its turns; the
state it keeps between turns is opaque text the dialogue store saves with the history.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol

from dialogue.ask import ASK_ROLE
from dialogue.ask.turn import AskRole
from dialogue.engine import DialogueEngine, TurnResult
from dialogue.errors import DialogueError
from dialogue.history import Utterance
from dialogue.sessionstore import DEFAULT_ROLE
from dialogue.trace.record import TraceRecorder


class UnknownRole(DialogueError, ValueError):
    """A role this service does not play; the message lists those it does."""


class Role(Protocol):
    def open(self, configuration: str) -> tuple[str, str]:
        """The opening line ("" for none) and the first role state; DialogueError: a bad configuration."""
        ...

    async def turn(
        self,
        configuration: str,
        role_state: str,
        text: str,
        *,
        speaker: str,
        history: Sequence[Utterance],
        locale: str | None,
        deadline: float,
        trace: TraceRecorder,
    ) -> tuple[TurnResult, str]:
        """One turn: the result (with its trace) and the role's new state."""
        ...


class DefaultRole:
    """The engine's own turn; the role keeps nothing."""

    def __init__(self, engine: DialogueEngine) -> None:
        self.engine = engine

    def open(self, configuration: str) -> tuple[str, str]:
        return "", ""

    async def turn(
        self,
        configuration: str,
        role_state: str,
        text: str,
        *,
        speaker: str,
        history: Sequence[Utterance],
        locale: str | None,
        deadline: float,
        trace: TraceRecorder,
    ) -> tuple[TurnResult, str]:
        result = await self.engine.turn(
            text, speaker=speaker, history=history, locale=locale, deadline=deadline, trace=trace
        )
        return result, role_state


class Roles:
    """The roles of one engine's dialogues, by name."""

    def __init__(self, engine: DialogueEngine) -> None:
        self._roles: dict[str, Role] = {DEFAULT_ROLE: DefaultRole(engine), ASK_ROLE: AskRole(engine)}

    @property
    def names(self) -> list[str]:
        return sorted(self._roles)

    def get(self, name: str) -> Role:
        role = self._roles.get(name)
        if role is None:
            raise UnknownRole(f"unsupported dialogue role {name!r}; supported: {self.names}")
        return role
