"""Shared helpers: KBs built from the eval scenes kept next to these tests (tests/dialogue/eval/)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from dialogue.reference.grounding import Snapshot, build_snapshot
from dialogue.reference.lexicon import Lexicon
from kb import KB

EVAL_DIR = Path(__file__).parent / "eval"


def scene_statements(name: str) -> list[str]:
    text = (EVAL_DIR / "scenes" / f"{name}.txt").read_text(encoding="utf-8")
    return [s.strip() for s in text.splitlines() if s.strip() and not s.strip().startswith("#")]


def scene_kb(name: str | None = None, *facts: str) -> KB:
    kb = KB()
    if name:
        kb.update(scene_statements(name))
    if facts:
        kb.update(list(facts))
    return kb


def lexicon_of(kb: KB) -> Lexicon:
    return Lexicon(build_snapshot(kb))


@pytest.fixture
def kitchen() -> Iterator[KB]:
    kb = scene_kb("kitchen")
    yield kb
    kb.close()


@pytest.fixture
def cups() -> Iterator[KB]:
    kb = scene_kb("two_cups")
    yield kb
    kb.close()


@pytest.fixture
def office() -> Iterator[KB]:
    kb = scene_kb("office")
    yield kb
    kb.close()


@pytest.fixture
def kitchen_snapshot(kitchen: KB) -> Snapshot:
    return build_snapshot(kitchen)
