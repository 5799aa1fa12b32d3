"""Helpers of the memory tests (their home, `home`, is shared: tests/dialogue/conftest.py)."""

from __future__ import annotations

from dialogue.reference.grounding import Snapshot, build_snapshot
from dialogue.reference.lexicon import Lexicon
from kb import KB
from tests.dialogue.conftest import english


def snapshot_of(kb: KB) -> Snapshot:
    return build_snapshot(kb)


def lexicon_of(kb: KB) -> Lexicon:
    return Lexicon(build_snapshot(kb), english())
