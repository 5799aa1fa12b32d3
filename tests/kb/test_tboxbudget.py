"""What one write may cost the reasoner (issue 26, item 1d): a subclass chain whose closed
hierarchy grows with the square of its length, and an RDF list of 200,000 items, are refused
with ``TBoxTooLarge`` before anything changes, without the memory they ask for;
writes within the bounds are reasoned as before, and recovery replays what was accepted."""

from __future__ import annotations

import resource
from collections.abc import Iterator
from pathlib import Path

import pytest

from kb import KB, KbError
from kb.errors import TBoxTooLarge
from kb.journal import Journal
from kb.tboxbudget import TBoxBounds

HEAD = "@prefix : <http://x.org/> . @prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .\n"


def chain(length: int, name: str = "C") -> str:
    return HEAD + "\n".join(f":{name}{i} rdfs:subClassOf :{name}{i + 1} ." for i in range(length))


def rdf_list(items: int) -> str:
    return HEAD + ":x :p (" + " ".join(f":i{i}" for i in range(items)) + ") ."


@pytest.fixture
def kb() -> Iterator[KB]:
    with KB() as k:
        k += "cup_1 isOn table_1"
        yield k


def state(kb: KB) -> tuple[int, int, list[bytes], list[str]]:
    return kb.revision, kb.size(), sorted(kb.export("nt").splitlines()), kb.models()


def _rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


@pytest.mark.parametrize(("document", "message"), [
    (chain(2000), r"would give http://x.org/C0 more than 256 superclasses"),
    (rdf_list(200_000), r"changes 400000 schema triples of model 'default'.*at most 20000"),
], ids=["2,000-class chain", "200,000-item list"])
def test_a_write_past_the_bounds_is_refused_and_changes_nothing(kb: KB, document: str, message: str) -> None:
    before, rss = state(kb), _rss_mb()
    with pytest.raises(TBoxTooLarge, match=message):
        kb.load_data(document, "turtle")
    assert state(kb) == before
    assert _rss_mb() - rss < 300, "the refusal took the memory the write asked for"


def test_the_total_of_links_is_bounded_too(kb: KB) -> None:
    before = state(kb)
    with pytest.raises(TBoxTooLarge, match="hold more than 50000 superclasses links"):
        kb.load_data(chain(250, "A") + chain(250, "B")[len(HEAD):] + chain(250, "D")[len(HEAD):], "turtle")
    assert state(kb) == before


def test_writes_within_the_bounds_are_reasoned(kb: KB) -> None:
    kb.load_data(chain(200) + "\n:thing a :C0 .", "turtle")
    assert kb.find(["<http://x.org/thing> rdf:type <http://x.org/C200>"])
    assert kb.find(["<http://x.org/C0> rdfs:subClassOf <http://x.org/C200>"])
    size = kb.size(inferred=False)
    kb.load_data(rdf_list(1000), "turtle")
    assert kb.size(inferred=False) == size + 2001  # first and rest of each item, and the link to it


def test_a_batch_of_several_models_is_refused_whole(kb: KB) -> None:
    before = state(kb)
    small = ["<http://x.org/A> rdfs:subClassOf <http://x.org/B>"]
    deep = [f"<http://x.org/C{i}> rdfs:subClassOf <http://x.org/C{i + 1}>" for i in range(400)]
    with pytest.raises(TBoxTooLarge):
        kb.apply_models({"alice": {"add": small, "remove": []}, "bob": {"add": deep, "remove": []}})
    assert state(kb) == before and kb.models() == ["default"]


def test_the_bounds_are_the_kb_s_to_set(tmp_path: Path) -> None:
    with pytest.raises(KbError, match="max_depth must be a positive integer"):
        TBoxBounds(max_depth=0)
    with KB(tbox_bounds=TBoxBounds(max_triples=5)) as small:
        with pytest.raises(TBoxTooLarge, match="at most 5"):
            small.load_data(chain(6), "turtle")
        small.load_data(chain(5), "turtle")
    # what a KB accepted is replayed at start whatever the bounds
    with KB(tbox_bounds=TBoxBounds(max_depth=1000, max_links=1_000_000)) as generous:
        journal = Journal(tmp_path)
        journal.recover(generous)
        generous.load_data(chain(300), "turtle")
        journal.close()
    with KB() as again:
        Journal(tmp_path).recover(again)
        assert again.find(["<http://x.org/C0> rdfs:subClassOf <http://x.org/C300>"])
