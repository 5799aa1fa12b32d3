"""Dialogue roles (chatbot_msgs `DialogueRole`): what a dialogue does with each turn, by role name.

`__default__` is the engine's turn (understand, ground, answer with intents); `__ask__` fills a form
(dialogue.ask). Each role opens a dialogue (an opening line, a first state) and runs its turns; the
state it keeps between turns is opaque text the dialogue store saves with the history, and says
where the dialogue is (`progress`: open, or over with its results).

A role's configuration is chatbot_msgs' opaque JSON: the default role reads no key of it, yet it
must be a JSON object (or nothing), as the contract says, so that a caller's mistake is refused.
A system update (`__system__`) and the robot's own words (`__assistant__`) are no person's words:
the default role has nothing to answer them (they are context for the next turns).

A default dialogue is open until someone ends it or the person takes leave ("bye", "see you later"):
that turn's result is `dialogue_terminal` and the dialogue is over (`done`, as a ROS Dialogue goal
then succeeds); whoever speaks in it next opens it again, as people start talking again.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from typing import Protocol

from dialogue.ask import ASK_ROLE
from dialogue.ask.turn import AskRole
from dialogue.engine import DialogueEngine, TurnResult
from dialogue.errors import DialogueError
from dialogue.history import Utterance, role_of
from dialogue.sessions.rolestate import Progress
from dialogue.sessions.store import DEFAULT_ROLE
from dialogue.trace.record import TraceRecorder


class UnknownRole(DialogueError, ValueError):
    """A role this service does not play; the message lists those it does."""


class BadConfiguration(DialogueError, ValueError):
    """A role configuration that is no JSON object; the message says what is wrong."""


def check_configuration(configuration: str, role: str) -> dict[str, object]:
    """The configuration as a JSON object ("" is an empty one); BadConfiguration otherwise."""
    if not configuration.strip():
        return {}
    try:
        value = json.loads(configuration)
    except json.JSONDecodeError as exc:
        raise BadConfiguration(f"the {role} role's configuration is not JSON ({exc.msg} at character "
                               f"{exc.pos}); give a JSON object, e.g. {{}}") from None
    if not isinstance(value, dict):
        raise BadConfiguration(f"the {role} role's configuration must be a JSON object, not "
                               f"{type(value).__name__}")
    return value


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

    def progress(self, role_state: str) -> Progress:
        """Where a dialogue whose role state is `role_state` is."""
        ...


#: The default role's state once the person took leave ("bye"); a later turn opens it again.
TOOK_LEAVE = "took leave"


class DefaultRole:
    """The engine's own turn; the role keeps only whether the person took leave ("bye"): the
    dialogue is then over (done, no results) until someone speaks in it again."""

    def __init__(self, engine: DialogueEngine) -> None:
        self.engine = engine

    def open(self, configuration: str) -> tuple[str, str]:
        check_configuration(configuration, DEFAULT_ROLE)
        return "", ""

    def progress(self, role_state: str) -> Progress:
        return Progress("done") if role_state == TOOK_LEAVE else Progress()

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
        if role_of(speaker) != "user":
            trace.note(f"{speaker}'s input is no person's words: nothing to answer")
            return self.engine.traced(TurnResult("", (), backend="recorded"), trace), role_state
        result = await self.engine.turn(
            text, speaker=speaker, history=history, locale=locale, deadline=deadline, trace=trace
        )
        return result, TOOK_LEAVE if result.dialogue_terminal else ""


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
