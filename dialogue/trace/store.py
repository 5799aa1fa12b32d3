"""The recent turn traces of each dialogue, bounded in memory: `max_turns` per dialogue (the most
recent), `max_dialogues` dialogues (the least recently traced are forgotten first).

Traces are this process's: with dialogues shared through a SPARQL store, each process keeps the
traces of the turns it ran.

>>> from dialogue.trace.record import TraceRecorder
>>> store = TraceStore(max_turns=2)
>>> for text in ("one", "two", "three"):
...     store.add("d1", TraceRecorder(input=text).finish(response="", backend="rules", answered_by="rules"))
>>> [t.input for t in store.recent("d1")], store.recent("nobody")
(['three', 'two'], None)
"""

from __future__ import annotations

import threading
from collections import OrderedDict, deque

from dialogue.trace.record import TurnTrace


class TraceStore:
    def __init__(self, max_turns: int = 20, max_dialogues: int = 128) -> None:
        if max_turns < 1 or max_dialogues < 1:
            raise ValueError("trace bounds must be positive")
        self.max_turns = max_turns
        self.max_dialogues = max_dialogues
        self._traces: OrderedDict[str, deque[TurnTrace]] = OrderedDict()
        self._lock = threading.Lock()  # reads may come from worker threads

    def add(self, dialogue_id: str, trace: TurnTrace) -> None:
        with self._lock:
            kept = self._traces.get(dialogue_id)
            if kept is None:
                kept = self._traces[dialogue_id] = deque(maxlen=self.max_turns)
            kept.append(trace)
            self._traces.move_to_end(dialogue_id)
            while len(self._traces) > self.max_dialogues:
                self._traces.popitem(last=False)

    def recent(self, dialogue_id: str, limit: int | None = None) -> list[TurnTrace] | None:
        """The dialogue's traces, most recent first (at most `limit`); None when none is kept."""
        with self._lock:
            kept = self._traces.get(dialogue_id)
            if kept is None:
                return None
            traces = list(reversed(kept))
        return traces if limit is None else traces[:limit]

    def forget(self, dialogue_id: str) -> None:
        with self._lock:
            self._traces.pop(dialogue_id, None)
