"""`situated bench model`'s bookkeeping, with a scripted streaming model instead of llama.cpp (the
real run needs the local extra and minutes; its figures are the benchmark's, never asserted)."""

from __future__ import annotations

import asyncio
import json
from typing import Any

import pytest

from bench import model as bench
from dialogue import intents as I
from dialogue.engine import DialogueEngine, EngineConfig
from dialogue.llm.testing import ScriptedModel
from dialogue.llm.worker import Completion
from kb import KB
from tests.dialogue.conftest import scene_kb


def grab(ack: str | None, obj: str = "cup_1") -> dict[str, Any]:
    return {"verbal_ack": ack, "user_intent": {"type": I.GRAB_OBJECT, "object": obj}}


def measured(answers: list[Any], streamed: bool, turns: int) -> list[Any]:
    kb: KB = scene_kb("kitchen", *bench.BOB)
    timed = bench._Timed(ScriptedModel(answers, chunk_size=3))  # type: ignore[arg-type]
    engine = DialogueEngine(kb, timed, EngineConfig(deadline=30))
    try:
        return asyncio.run(bench._turns(engine, timed, range(turns), streamed))
    finally:
        kb.close()


def test_a_streamed_turn_notes_the_first_word_and_the_ack_before_its_end() -> None:
    (turn,) = measured([grab("On my way now.")], streamed=True, turns=1)
    assert turn.first_word is not None and turn.ack is not None
    assert turn.first_word <= turn.ack <= turn.seconds
    assert len(turn.requests) == 1 and not turn.fell_back


def test_repairs_and_fallbacks_are_counted_and_reported() -> None:
    turns = measured([grab("OK"), grab("A", "unicorn"), grab("B", "unicorn")], streamed=False, turns=2)
    assert [len(t.requests) for t in turns] == [1, 2] and [t.fell_back for t in turns] == [False, True]
    assert all(t.first_word is None and t.ack is None for t in turns)
    report = bench.Report(threads=1)
    report.add("scripted", bench.CONFIGS["service"], turns)
    table = report.table((1.0, 2.0, 3.0), (1.5, 2.0, 3.0))
    assert "load average (1/5/15 min) before 1.00 2.00 3.00, after 1.50 2.00 3.00" in table
    row = table.splitlines()[-1]
    assert row.startswith("| scripted | service: prefix cached, grammar |") and "| 1/2 | 1 | — | — |" in row


@pytest.mark.parametrize("argv", [["--models", "gpt-9"], ["--turns", "0"], ["--threads", "0"], ["--models", ","],
                                  ["--runs", "service,fast"]])
def test_bad_options_are_refused(argv: list[str]) -> None:
    with pytest.raises(SystemExit) as exit_:
        bench.main(argv)
    assert exit_.value.code == 2


class FakeRunner:
    """Bare llama.cpp's place: notes each prompt, answers as told."""

    def __init__(self, answers: list[str]) -> None:
        self.answers = answers
        self.prompts: list[tuple[list[dict[str, str]], dict[str, Any]]] = []

    def generate(self, messages: list[dict[str, str]], schema: dict[str, Any], expired: Any) -> Completion:
        self.prompts.append((messages, schema))
        return Completion(self.answers[len(self.prompts) - 1], "stop", 700, 12, 500)


def test_the_bare_baseline_completes_the_services_own_prompts() -> None:
    kb: KB = scene_kb("kitchen", *bench.BOB)
    scripted = ScriptedModel([grab("OK"), grab("OK")])
    engine = DialogueEngine(kb, scripted, EngineConfig(deadline=30))
    runner = FakeRunner([json.dumps(grab("OK")), json.dumps(grab("No", "unicorn"))])
    try:
        asyncio.run(bench._turns(engine, bench._Timed(scripted), range(2), False))  # type: ignore[arg-type]
        turns = bench._bare_turns(engine, runner, range(2))
    finally:
        kb.close()
    assert [[m.as_dict() for m in r.messages] for r in scripted.requests] == [m for m, _ in runner.prompts]
    assert [r.schema for r in scripted.requests] == [s for _, s in runner.prompts]
    assert [t.valid for t in turns] == [True, False] and not any(t.fell_back for t in turns)
    report = bench.Report(threads=1)
    report.add("scripted", bench.CONFIGS["bare"], turns)
    row = report.table((1.0, 1.0, 1.0), (1.0, 1.0, 1.0)).splitlines()[-1]
    assert "| baseline: bare llama.cpp, same prompt |" in row and "| 500 + 200 | 12 | 1/2 | 0 |" in row
