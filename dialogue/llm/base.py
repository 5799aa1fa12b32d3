"""The one protocol every model backend implements, and what travels through it.

A request carries the rendered chat messages and the turn's JSON schema for text models, and the
structured turn context so that offline models (`rules`, the test models) work without parsing text.

Callers never test a model's class: they ask the model. `prescreen` answers from the structured
context before any prompt is built (the rules' fast path), `llm` names the model that reads prompts
(None when nothing behind this model does), `probe` says whether it can answer (/health),
`self_check` and `setup_hint` serve `situated doctor`, and `aclose` releases what the model holds
(its HTTP client, its worker process). Backends subclass `ChatModel` explicitly to inherit the
defaults.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, Literal, Protocol, runtime_checkable

from dialogue.errors import DialogueError
from dialogue.history import Utterance
from dialogue.reference.grounding import Entity, Snapshot
from dialogue.reference.lexicon import Lexicon
from dialogue.schema import ChatbotResponse
from dialogue.understanding.said import Said

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
    #: The entities the prompt and the schema show, most relevant first (`reference.relevance`;
    #: the engine's is ranked when first read); None: ranked without the utterance.
    focus: Sequence[Entity] | None = None
    #: The lexicon of `snapshot` the engine already keeps (the rules read it rather than keeping
    #: a second one of every entity); None: the model makes its own.
    lexicon: Lexicon | None = None
    #: The turn's words as the engine read them, once (dialogue.understanding.said), in the
    #: lexicon's language: the rules read these rather than the text again; None: read the text.
    said: Said | None = None


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

    `understood` is False when an offline model knows it did not understand the input: a wrapper
    (hybrid) then asks the model behind it, and the engine never takes it for an answer.
    """

    content: str
    done_reason: str | None = "stop"
    understood: bool = True
    extra: dict[str, Any] = field(default_factory=dict)


class ModelError(DialogueError):
    """The backend failed: unreachable, HTTP error, truncated or empty output. Message says which."""


@dataclass(frozen=True)
class EarlyAnswer:
    """An answer given from the turn's structured context alone, before any prompt is built. It goes
    through the same validation and grounding as a model's answer."""

    answer: ChatbotResponse
    #: Who answered (the `backend` of the turn's result).
    backend: str
    #: The answer asks the speaker which referent they meant.
    clarify: bool = False
    #: The answer proposes a reading and asks whether to act on it ("Shall I...?"): no claim of
    #: understanding, its intents held until the speaker says yes.
    confirm: bool = False
    #: The person took leave ("bye"): the answer ends the conversation (the turn's `dialogue_terminal`).
    ends: bool = False
    #: False: the model did not understand the turn and the answer is only why ("Sorry, I don't see
    #: any bagget": a thing absent, or misheard?). A model behind reads the turn instead; alone,
    #: the reason is a better reply than "I did not understand", and claims nothing.
    understood: bool = True


@dataclass(frozen=True)
class SelfCheck:
    """A backend's own check of its setup (`situated doctor`), for backends a turn cannot check."""

    ok: bool
    detail: str
    fix: str = ""


DEFAULT_SETUP_HINT = "check the model backend named by --llm"


@runtime_checkable
class ChatModel(Protocol):
    """An async chat backend. `timeout` is the time left in the turn, in seconds."""

    @property
    def name(self) -> str: ...

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult: ...

    @property
    def llm(self) -> ChatModel | None:
        """The model that reads prompts: this one, the model a wrapper asks, or None when the
        model answers from the structured context only (then a turn `prescreen` did not answer is
        not understood)."""
        return self

    def prescreen(self, context: TurnContext) -> EarlyAnswer | None:
        """An answer without a prompt (synchronous and cheap: it runs on every turn), or None."""
        return None

    @property
    def setup_hint(self) -> str:
        """How to fix a setup where this backend does not answer."""
        return DEFAULT_SETUP_HINT

    async def self_check(self, timeout: float) -> SelfCheck | None:
        """A check of the setup by the backend itself; None: a real turn request checks it."""
        return None

    async def probe(self, timeout: float) -> dict[str, Any]:
        """For /health: ``{"remote", "reachable", "detail"}`` and whatever else the backend reports
        of its own state. A remote backend sends one cheap request to its server."""
        return {"remote": False, "reachable": True, "detail": "in-process"}

    async def preload(self) -> None:
        """Get ready for the first turn (load the model), so that it does not pay for it."""
        return None

    async def aclose(self) -> None:
        """Release what the model holds, at shutdown, on the event loop that used it."""
        return None
