"""The one protocol every model backend implements, and what travels through it.

A request carries the rendered chat messages and the turn's JSON schema for text models, and the
structured turn context so that offline models (`rules`, the test models) work without parsing text.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Literal, Protocol, runtime_checkable

from dialogue.errors import DialogueError
from dialogue.history import Utterance
from dialogue.reference.grounding import Entity, Snapshot

MessageRole = Literal["system", "user", "assistant"]


@dataclass(frozen=True)
class ChatMessage:
    role: MessageRole
    content: str

    def as_dict(self) -> dict[str, str]:
        return {"role": self.role, "content": self.content}


@dataclass(frozen=True)
class TurnContext:
    """What the turn is about, in structured form."""

    text: str
    speaker: str
    snapshot: Snapshot
    history: tuple[Utterance, ...] = ()
    locale: str | None = None
    robot_name: str = "robot"
    #: The entities the prompt and the schema show, most relevant first (`reference.relevance`);
    #: None: ranked without the utterance.
    focus: tuple[Entity, ...] | None = None


@dataclass(frozen=True)
class ChatRequest:
    messages: tuple[ChatMessage, ...]
    schema: dict[str, Any]
    context: TurnContext
    #: True for the repair request that follows an invalid answer.
    repair: bool = False


@dataclass(frozen=True)
class ChatResult:
    """The raw content (validated later by the engine) and why generation stopped.

    `understood` is False when an offline model knows it did not understand the input, so that the
    engine can fall back (to the LLM in hybrid mode, else to `__raw_user_input__`).
    """

    content: str
    done_reason: str | None = "stop"
    understood: bool = True
    extra: dict[str, Any] = field(default_factory=dict)


class ModelError(DialogueError):
    """The backend failed: unreachable, HTTP error, truncated or empty output. Message says which."""


@runtime_checkable
class ChatModel(Protocol):
    """An async chat backend. `timeout` is the time left in the turn, in seconds."""

    @property
    def name(self) -> str: ...

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult: ...
