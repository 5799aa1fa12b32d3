"""Dialogue history: utterances with their chat role, bounded by turns and characters (D12)."""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from typing import Literal

Role = Literal["user", "assistant", "system"]

SYSTEM_USER_ID = "__system__"
ASSISTANT_USER_ID = "__assistant__"


def role_of(user_id: str) -> Role:
    """`__assistant__` speaks as the assistant, `__system__` as the system, anyone else as a user (D14)."""
    if user_id == ASSISTANT_USER_ID:
        return "assistant"
    if user_id == SYSTEM_USER_ID:
        return "system"
    return "user"


@dataclass(frozen=True)
class Utterance:
    speaker: str
    text: str
    #: The chat role it was said in, found once: the readers of every turn scan the history by it
    #: (some 50 utterances, several times a turn).
    role: Role = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "role", role_of(self.speaker))


class History:
    """The last `max_turns` utterances, further trimmed (oldest first) to `max_chars` characters."""

    def __init__(self, max_turns: int = 20, max_chars: int = 4000) -> None:
        if max_turns < 1 or max_chars < 1:
            raise ValueError("history limits must be positive")
        self.max_chars = max_chars
        self._items: deque[Utterance] = deque(maxlen=max_turns)
        self._chars = 0  # of the texts kept: a turn's history is rebuilt one add at a time

    @classmethod
    def of(cls, utterances: Iterable[Utterance], max_turns: int = 20, max_chars: int = 4000) -> History:
        """What adding `utterances` one by one keeps, built at once: a dialogue's stored history is
        taken up each turn (some 50 utterances), and adding them one at a time was a tenth of the
        turn's own work. The same utterances: the latest `max_turns` of those not blank, then the
        oldest dropped while they hold more than `max_chars` characters (never the latest)."""
        history = cls(max_turns, max_chars)
        said = [u for u in utterances if u.text.strip()]
        items = history._items
        items.extend(said[-max_turns:])
        history._chars = sum(len(u.text) for u in items)
        while len(items) > 1 and history._chars > max_chars:
            history._chars -= len(items.popleft().text)
        return history

    def add(self, speaker: str, text: str) -> None:
        """Keep an utterance; a blank one says nothing and is not kept."""
        if not text.strip():
            return
        if len(self._items) == self._items.maxlen:  # the oldest goes to make room
            self._chars -= len(self._items[0].text)
        self._items.append(Utterance(speaker, text))
        self._chars += len(text)
        while len(self._items) > 1 and self._chars > self.max_chars:
            self._chars -= len(self._items.popleft().text)

    def clear(self) -> None:
        self._items.clear()
        self._chars = 0

    def __iter__(self) -> Iterator[Utterance]:
        return iter(tuple(self._items))

    def __len__(self) -> int:
        return len(self._items)

    def snapshot(self) -> tuple[Utterance, ...]:
        return tuple(self._items)
