"""The recent turn traces of each dialogue, bounded in memory: `max_turns` per dialogue (the most
recent), `max_dialogues` dialogues (the least recently traced are forgotten first), and
`max_chars` characters in all (`TurnTrace.chars`), because a model turn's trace holds its prompts
and schema and can weigh a hundred times a rules turn's: past the budget, the oldest traces of the
least recently traced dialogues go first, and a trace alone over the budget is not kept.

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

#: About 8 MB of text at most: a few hundred model turns with their prompts, thousands of rules turns.
MAX_CHARS = 8_000_000


class TraceStore:
    def __init__(self, max_turns: int = 20, max_dialogues: int = 128, max_chars: int = MAX_CHARS) -> None:
        if max_turns < 1 or max_dialogues < 1 or max_chars < 1:
            raise ValueError("trace bounds must be positive")
        self.max_turns = max_turns
        self.max_dialogues = max_dialogues
        self.max_chars = max_chars
        #: Each dialogue's traces, oldest first, with their sizes; dialogues least recently traced first.
        self._traces: OrderedDict[str, deque[tuple[TurnTrace, int]]] = OrderedDict()
        self._chars = 0
        self._lock = threading.Lock()  # reads may come from worker threads

    @property
    def chars(self) -> int:
        """The characters the kept traces hold, as `TurnTrace.chars` counts them."""
        return self._chars

    def add(self, dialogue_id: str, trace: TurnTrace) -> None:
        size = trace.chars()
        with self._lock:
            kept = self._traces.get(dialogue_id)
            if kept is None:
                kept = self._traces[dialogue_id] = deque()
            self._traces.move_to_end(dialogue_id)
            kept.append((trace, size))
            self._chars += size
            if len(kept) > self.max_turns:
                self._chars -= kept.popleft()[1]
            while len(self._traces) > self.max_dialogues:
                self._drop(next(iter(self._traces)), whole=True)
            while self._chars > self.max_chars:
                self._drop(next(iter(self._traces)), whole=False)

    def _drop(self, dialogue_id: str, whole: bool) -> None:
        kept = self._traces[dialogue_id]
        while kept:
            self._chars -= kept.popleft()[1]
            if not whole:
                break
        if not kept:
            del self._traces[dialogue_id]

    def recent(self, dialogue_id: str, limit: int | None = None) -> list[TurnTrace] | None:
        """The dialogue's traces, most recent first (at most `limit`); None when none is kept."""
        with self._lock:
            kept = self._traces.get(dialogue_id)
            if kept is None:
                return None
            traces = [trace for trace, _ in reversed(kept)]
        return traces if limit is None else traces[:limit]

    def forget(self, dialogue_id: str) -> None:
        with self._lock:
            for _, size in self._traces.pop(dialogue_id, ()):
                self._chars -= size
