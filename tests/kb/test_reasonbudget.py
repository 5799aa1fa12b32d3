"""What one write's facts may cost the reasoner (issue 26, the rerun of attack 1d): a chain along
a transitive property with an inverse (``behind``/``inFrontOf``) closes into the square of its
length — 300 statements took 23 s and 364,000 inferred triples under the KB lock, 400 took 60 s —
so a write past its allowance of derivation steps is refused whole, quickly; ordinary writes and
bulk loads are reasoned as before, and recovery replays whatever was accepted."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from kb import KB, KbError
from kb.errors import ReasoningTooLarge
from kb.journal import Journal
from kb.reasonbudget import ReasoningBounds


def chain(length: int, name: str = "o", start: int = 0) -> list[str]:
    return [f"{name}{i} behind {name}{i + 1}" for i in range(start, start + length)]


@pytest.fixture
def kb() -> Iterator[KB]:
    with KB() as k:
        k += "cup_1 isOn table_1"
        yield k


def state(kb: KB) -> tuple[int, int, list[bytes], list[str]]:
    return kb.revision, kb.size(), sorted(kb.export("nt").splitlines()), kb.models()


def test_a_transitive_chain_past_the_allowance_is_refused_quickly_and_changes_nothing(kb: KB) -> None:
    before = state(kb)
    with pytest.raises(ReasoningTooLarge, match=r"more than 204800 derivation steps.*Nothing was written"):
        kb.add(chain(300))
    # before: accepted after 23 s, with 364,000 inferred triples
    assert state(kb) == before


def test_a_refused_retraction_changes_nothing(tmp_path: Path) -> None:
    bounds = ReasoningBounds(max_steps=50_000, per_statement=1)
    with KB(reasoning_bounds=bounds) as kb:
        for start in range(0, 60, 5):  # each write small enough
            kb.add(chain(5, start=start))
        assert kb.find(["o0 behind o60"])
        before = state(kb)
        with pytest.raises(ReasoningTooLarge):
            kb.remove(["o30 behind o31"])  # over-deletes most of the closure, then re-derives it
        assert state(kb) == before
        assert kb.find(["o0 behind o60"]) and kb.find(["o60 inFrontOf o0"])


def test_a_batch_of_several_models_is_refused_whole(kb: KB) -> None:
    before = state(kb)
    with pytest.raises(ReasoningTooLarge):
        kb.apply_models({"alice": {"add": chain(10), "remove": []}, "bob": {"add": chain(300), "remove": []}})
    assert state(kb) == before and kb.models() == ["default"]


def test_ordinary_writes_and_a_chain_within_the_allowance_are_reasoned(kb: KB) -> None:
    kb.add(chain(50))
    assert kb.find(["o0 behind o50"]) and kb.find(["o50 inFrontOf o0"])
    # a bulk load of facts that derive a few triples each: its allowance grows with it
    people = [f"person_{i} rdf:type Human" for i in range(5000)]
    sightings = [f"person_{i} sees cup_{i % 300}" for i in range(5000)]
    kb.add(people + sightings + [f"cup_{i} rdf:type dbr:Cup" for i in range(300)])
    assert kb.find(["person_4999 rdf:type Agent"])


def test_the_bounds_are_the_kb_s_to_set_and_recovery_replays_what_was_accepted(tmp_path: Path) -> None:
    with pytest.raises(KbError, match="max_steps must be a positive integer"):
        ReasoningBounds(max_steps=0)
    small = ReasoningBounds(max_steps=60_000, per_statement=1)
    with KB(reasoning_bounds=small) as kb:
        journal = Journal(tmp_path)
        journal.recover(kb)
        with pytest.raises(ReasoningTooLarge, match="more than 60080 derivation steps"):
            kb.add(chain(80))
        for start in range(0, 80, 5):  # the same chain in parts, each within the allowance
            kb.add(chain(5, start=start))
        journal.close()
    # replayed in one batch, the chain costs more than one write may: recovery takes it all
    with KB(reasoning_bounds=small) as again:
        Journal(tmp_path).recover(again)
        assert again.find(["o0 behind o80"]) and again.find(["o80 inFrontOf o0"])
