"""Where dialogue sessions live: the `SessionStore` protocol, the session state, and `MemorySessions`.

A dialogue's state is a plain value (`DialogueState`, JSON with `to_json` / `from_json`) that the
`DialogueManager` loads at the start of a turn and saves at its end, so any process sharing the
store can continue a dialogue another one started. A pending clarification needs no state of its
own: the engine finishes it from the history (the robot's question right after the request).

Stores hold at most `max_dialogues` dialogues, counting `default` whether it is stored or not;
creating one beyond that drops the least recently saved others, never `default`.
"""

from __future__ import annotations

import json
import threading
from collections import OrderedDict
from dataclasses import dataclass
from typing import Any, ClassVar, Protocol

from dialogue.errors import DialogueError
from dialogue.history import Utterance

DEFAULT_DIALOGUE = "default"
DEFAULT_ROLE = "__default__"
#: Written into every stored state; a state of another format is refused, not guessed at.
STATE_FORMAT = 1


class StateError(DialogueError, ValueError):
    """A stored dialogue state that cannot be read; the message says what is wrong with it."""


@dataclass(frozen=True)
class DialogueState:
    id: str
    role: str = DEFAULT_ROLE
    locale: str | None = None
    #: The role's configuration, opaque (a JSON string per chatbot_msgs/DialogueRole).
    configuration: str = ""
    history: tuple[Utterance, ...] = ()
    #: When the dialogue was last saved (seconds since the epoch); orders the eviction.
    last_used: float = 0.0
    #: What the role keeps between turns (the ask role: its form), opaque JSON text.
    role_state: str = ""

    def to_json(self) -> str:
        # ASCII only: the text travels safely through any store, even lone surrogates from JSON input.
        return json.dumps(
            {
                "format": STATE_FORMAT,
                "id": self.id,
                "role": self.role,
                "locale": self.locale,
                "configuration": self.configuration,
                "history": [{"speaker": u.speaker, "text": u.text} for u in self.history],
                "last_used": self.last_used,
                "role_state": self.role_state,
            },
            ensure_ascii=True,
            separators=(",", ":"),
        )

    @classmethod
    def from_json(cls, text: str) -> DialogueState:
        try:
            data = json.loads(text)
        except json.JSONDecodeError as exc:
            raise StateError(f"stored dialogue state is not JSON: {exc}") from None
        if not isinstance(data, dict) or data.get("format") != STATE_FORMAT:
            raise StateError(f"stored dialogue state is not an object of format {STATE_FORMAT}")
        history = data.get("history")
        if not isinstance(history, list) or not all(_is_utterance(u) for u in history):
            raise StateError("stored dialogue history must be a list of {speaker, text} strings")
        locale = data.get("locale")
        last_used = data.get("last_used")
        role_state = data.get("role_state", "")  # absent from states saved before roles kept any
        if not isinstance(role_state, str):
            raise StateError("stored dialogue role_state must be a string")
        strings = (data.get("id"), data.get("role"), data.get("configuration"))
        if not all(isinstance(s, str) for s in strings) or not isinstance(locale, str | None):
            raise StateError("stored dialogue id, role, configuration and locale must be strings")
        if not isinstance(last_used, int | float) or isinstance(last_used, bool):
            raise StateError("stored dialogue last_used must be a number")
        return cls(
            data["id"],
            data["role"],
            locale,
            data["configuration"],
            tuple(Utterance(u["speaker"], u["text"]) for u in history),
            float(last_used),
            role_state,
        )


def _is_utterance(item: Any) -> bool:
    return isinstance(item, dict) and all(isinstance(item.get(key), str) for key in ("speaker", "text"))


class SessionStore(Protocol):
    """Dialogue states by id. Calls may block (`blocking`): async code runs those in a thread."""

    #: True when calls do I/O, so the manager runs them off the event loop.
    blocking: ClassVar[bool]
    max_dialogues: int

    def load(self, dialogue_id: str) -> DialogueState | None:
        """The stored state, or None when the store holds no such dialogue."""
        ...

    def save(self, state: DialogueState, *, create: bool = False) -> None:
        """Store `state` in place of the stored one. Without `create` a dialogue the store does not
        hold (ended meanwhile) is not stored again; with it, dialogues beyond the bound are dropped."""
        ...

    def delete(self, dialogue_id: str) -> None:
        """Forget a dialogue (no error when it is not stored)."""
        ...

    def ids(self) -> list[str]:
        """The stored dialogues, least recently saved first."""
        ...


def check_bound(max_dialogues: int) -> int:
    if max_dialogues < 1:
        raise ValueError("max_dialogues must be at least 1")
    return max_dialogues


class MemorySessions:
    """States in this process's memory (the default): nothing is shared with other processes."""

    blocking: ClassVar[bool] = False

    def __init__(self, max_dialogues: int = 256) -> None:
        self.max_dialogues = check_bound(max_dialogues)
        self._states: OrderedDict[str, DialogueState] = OrderedDict()
        # Sync callers may use the store from worker threads.
        self._lock = threading.Lock()

    def load(self, dialogue_id: str) -> DialogueState | None:
        with self._lock:
            return self._states.get(dialogue_id)

    def save(self, state: DialogueState, *, create: bool = False) -> None:
        with self._lock:
            if not create and state.id not in self._states:
                return
            self._states[state.id] = state
            self._states.move_to_end(state.id)
            others = [i for i in self._states if i != DEFAULT_DIALOGUE]
            # `default` takes one place of the bound whether it is stored or not.
            for oldest in others[: max(0, len(others) - (self.max_dialogues - 1))]:
                del self._states[oldest]

    def delete(self, dialogue_id: str) -> None:
        with self._lock:
            self._states.pop(dialogue_id, None)

    def ids(self) -> list[str]:
        with self._lock:
            return list(self._states)
