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


def model_trace(text: str, prompt_chars: int) -> TurnTrace:
    recorder = TraceRecorder(input=text)
    exchange = recorder.request("scripted", [("system", "x" * prompt_chars)], {"type": "object"})
    recorder.answered(exchange, '{"reply": "ok"}', "stop", 0.0)
    return recorder.finish(response="ok", backend="scripted", answered_by="model")


def test_the_character_budget_forgets_the_oldest_traces_of_the_least_recent_dialogues() -> None:
    store = TraceStore(max_turns=10, max_dialogues=10, max_chars=3500)
    store.add("a", model_trace("a0", 1000))
    store.add("a", model_trace("a1", 1000))
    store.add("b", model_trace("b0", 1000))
    assert store.chars == sum(t.chars() for d in ("a", "b") for t in store.recent(d) or [])
    assert 3000 < store.chars <= 3500
    store.add("b", model_trace("b1", 1000))  # over the budget: a's oldest goes, not b's
    assert [t.input for t in store.recent("a") or []] == ["a1"]
    assert [t.input for t in store.recent("b") or []] == ["b1", "b0"]
    store.add("b", model_trace("b2", 1000))  # a has nothing left: it is forgotten
    assert store.recent("a") is None
    assert [t.input for t in store.recent("b") or []] == ["b2", "b1", "b0"]
    store.forget("b")
    assert store.chars == 0


def test_a_trace_alone_over_the_budget_is_not_kept() -> None:
    store = TraceStore(max_chars=500)
    store.add("a", trace("small"))
    store.add("a", model_trace("huge", 1000))
    assert store.recent("a") is None and store.chars == 0


def test_the_budget_counts_what_the_trace_holds() -> None:
    light, heavy = trace("hello"), model_trace("hello", 5000)
    assert light.chars() == len("hello")
    assert heavy.chars() > 5000 + len('{"reply": "ok"}')
    with pytest.raises(ValueError, match="positive"):
        TraceStore(max_chars=0)
