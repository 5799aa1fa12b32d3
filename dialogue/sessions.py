"""Dialogues (chatbot_msgs DialogueInteraction semantics): many at once, each with a bounded history.

`default` always exists. `__assistant__` and `__system__` utterances are recorded with the assistant
and system roles (D14); `response_expected=False` only records. A turn on a dialogue sees that
dialogue's history, and the answer (with the user's words) is appended after the turn.
"""

from __future__ import annotations

import asyncio
import uuid
from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass, field

from dialogue.engine import DialogueEngine, TurnResult
from dialogue.history import ASSISTANT_USER_ID, History, Utterance

DEFAULT_DIALOGUE = "default"
DEFAULT_ROLE = "__default__"
SUPPORTED_ROLES = frozenset({DEFAULT_ROLE})


class DialogueError(ValueError):
    """Unknown dialogue id, unsupported role, or a request that cannot be served; message says which."""


@dataclass
class Dialogue:
    id: str
    role: str = DEFAULT_ROLE
    locale: str | None = None
    configuration: str = ""
    history: History = field(default_factory=History)
    lock: asyncio.Lock = field(default_factory=asyncio.Lock, repr=False)


class DialogueManager:
    """Keeps dialogues by id (least recently used ones beyond `max_dialogues` are dropped)."""

    def __init__(
        self, engine: DialogueEngine, *, max_dialogues: int = 256, max_turns: int = 20, max_chars: int = 4000
    ) -> None:
        if max_dialogues < 1:
            raise ValueError("max_dialogues must be at least 1")
        self.engine = engine
        self.max_dialogues = max_dialogues
        self.max_turns = max_turns
        self.max_chars = max_chars
        self._dialogues: OrderedDict[str, Dialogue] = OrderedDict()
        self._new(DEFAULT_DIALOGUE, DEFAULT_ROLE, None, "")

    def _new(self, dialogue_id: str, role: str, locale: str | None, configuration: str) -> Dialogue:
        dialogue = Dialogue(dialogue_id, role, locale, configuration, History(self.max_turns, self.max_chars))
        self._dialogues[dialogue_id] = dialogue
        while len(self._dialogues) > self.max_dialogues:
            oldest = next(d for d in self._dialogues if d != DEFAULT_DIALOGUE)
            del self._dialogues[oldest]
        return dialogue

    def start(
        self,
        role: str = DEFAULT_ROLE,
        locale: str | None = None,
        configuration: str = "",
        dialogue_id: str | None = None,
    ) -> Dialogue:
        if role not in SUPPORTED_ROLES:
            raise DialogueError(f"unsupported dialogue role {role!r}; supported: {sorted(SUPPORTED_ROLES)}")
        if dialogue_id is not None and dialogue_id in self._dialogues:
            raise DialogueError(f"dialogue {dialogue_id!r} already exists")
        return self._new(dialogue_id or str(uuid.uuid4()), role, locale, configuration)

    def get(self, dialogue_id: str) -> Dialogue:
        try:
            dialogue = self._dialogues[dialogue_id]
        except KeyError:
            raise DialogueError(f"unknown dialogue {dialogue_id!r}; start it first") from None
        self._dialogues.move_to_end(dialogue_id)
        return dialogue

    def end(self, dialogue_id: str) -> None:
        """Forget a dialogue; ending `default` only clears its history (it always exists)."""
        dialogue = self.get(dialogue_id)
        if dialogue_id == DEFAULT_DIALOGUE:
            dialogue.history.clear()
        else:
            del self._dialogues[dialogue_id]

    def ids(self) -> list[str]:
        return list(self._dialogues)

    async def interact(
        self,
        user_id: str,
        text: str,
        *,
        dialogue_id: str = DEFAULT_DIALOGUE,
        locale: str | None = None,
        response_expected: bool = True,
        history: Sequence[Utterance] | None = None,
    ) -> TurnResult:
        """One DialogueInteraction. `history` (the 4.0.0 stateless shape) replaces the stored one."""
        if not user_id:
            raise DialogueError("user_id is required")
        dialogue = self.get(dialogue_id)
        async with dialogue.lock:
            if history is not None:
                dialogue.history.clear()
                for utterance in history:
                    dialogue.history.add(utterance.speaker, utterance.text)
            if not response_expected:
                dialogue.history.add(user_id, text)
                return TurnResult("", (), backend="recorded")
            result = await self.engine.turn(
                text, speaker=user_id, history=dialogue.history.snapshot(), locale=locale or dialogue.locale
            )
            dialogue.history.add(user_id, text)
            if result.response:
                dialogue.history.add(ASSISTANT_USER_ID, result.response)
            return result
