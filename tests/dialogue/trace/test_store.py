"""Traces kept per dialogue, bounded in turns and dialogues."""

from __future__ import annotations

import pytest

from dialogue.trace.record import TraceRecorder, TurnTrace
from dialogue.trace.store import TraceStore


def trace(text: str) -> TurnTrace:
    return TraceRecorder(input=text).finish(response="", backend="rules", answered_by="rules")


def test_most_recent_first_and_bounded() -> None:
    store = TraceStore(max_turns=3, max_dialogues=2)
    for i in range(5):
        store.add("a", trace(f"a{i}"))
    assert [t.input for t in store.recent("a") or []] == ["a4", "a3", "a2"]
    assert [t.input for t in store.recent("a", limit=1) or []] == ["a4"]
    store.add("b", trace("b0"))
    store.add("c", trace("c0"))  # a third dialogue: the least recently traced one goes
    assert store.recent("a") is None and store.recent("c") is not None
    store.forget("c")
    assert store.recent("c") is None


def test_bad_bounds() -> None:
    with pytest.raises(ValueError, match="positive"):
        TraceStore(max_turns=0)
