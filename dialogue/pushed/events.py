"""One pushed intent: the intent as emitted (the `Intent` JSON shape), where it came from, its number.

    {"seq": 12, "time": 1717237800.5, "origin": "dialogue", "dialogue_id": "default",
     "response": "OK, I will bring the cup to you.",
     "intent": {"intent": "__intent_bring_object__", "data": {...}, "source": "person_alice", ...}}

`origin` is `dialogue` (a turn of `dialogue_id`) or `initiative` (the robot's own, e.g. greeting a
person who engaged; no dialogue). `response` is what the robot says with the intent: a turn's reply
travels with its first intent, a greeting's words with its GREET. Before a bus numbers it, an intent
is `Emitted` (what a read replica hands to the writer's bus). Each one's `size` is the bytes of its
JSON, what it costs a buffer and an answer that carries it.
"""

from __future__ import annotations

import json
from collections.abc import Iterable
from dataclasses import dataclass
from functools import cached_property
from typing import Any, Literal

from dialogue.intents import Intent
from dialogue.sessions.observers import TurnRecord

Origin = Literal["dialogue", "initiative"]
ORIGINS: frozenset[str] = frozenset({"dialogue", "initiative"})


def json_bytes(value: Any) -> int:
    """The bytes of `value` as compact UTF-8 JSON."""
    return len(json.dumps(value, ensure_ascii=False, separators=(",", ":")).encode())


@dataclass(frozen=True)
class Pushed:
    seq: int
    time: float
    origin: Origin
    intent: Intent
    dialogue_id: str | None = None
    response: str = ""

    def as_json(self) -> dict[str, Any]:
        return {"seq": self.seq, "time": self.time, "origin": self.origin, "dialogue_id": self.dialogue_id,
                "response": self.response, "intent": self.intent.model_dump(mode="json")}

    @cached_property
    def size(self) -> int:
        return json_bytes(self.as_json())


@dataclass(frozen=True)
class Emitted:
    """An intent as emitted, not numbered yet; `time` when (seconds since the epoch)."""

    origin: Origin
    intent: Intent
    dialogue_id: str | None
    response: str
    time: float

    def as_json(self) -> dict[str, Any]:
        return {"time": self.time, "origin": self.origin, "dialogue_id": self.dialogue_id,
                "response": self.response, "intent": self.intent.model_dump(mode="json")}

    @property
    def size(self) -> int:
        return json_bytes(self.as_json())


def emitted(record: TurnRecord) -> list[Emitted]:
    """A turn's intents as emitted, in order, its reply with the first."""
    result = record.result
    return [Emitted("dialogue", intent, record.dialogue_id, result.response if n == 0 else "", record.at)
            for n, intent in enumerate(result.intents)]


@dataclass(frozen=True)
class IntentFilter:
    """Which events a subscriber wants: each non-empty set must contain the event's value."""

    sources: frozenset[str] = frozenset()
    intents: frozenset[str] = frozenset()
    origins: frozenset[str] = frozenset()
    dialogues: frozenset[str] = frozenset()

    @classmethod
    def of(cls, sources: Iterable[str] = (), intents: Iterable[str] = (), origins: Iterable[str] = (),
           dialogues: Iterable[str] = ()) -> IntentFilter:
        """A filter from lists (query parameters); ValueError naming an unknown origin."""
        unknown = set(origins) - ORIGINS
        if unknown:
            raise ValueError(f"unknown origin {sorted(unknown)}; expected one of {sorted(ORIGINS)}")
        return cls(frozenset(sources), frozenset(intents), frozenset(origins), frozenset(dialogues))

    def matches(self, event: Pushed) -> bool:
        return ((not self.sources or event.intent.source in self.sources)
                and (not self.intents or event.intent.intent in self.intents)
                and (not self.origins or event.origin in self.origins)
                and (not self.dialogues or event.dialogue_id in self.dialogues))
