"""``KB.summary``: what /health reports, read without the KB lock, always one committed state."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest

from kb import KB
from kb.errors import StorageError
from kb.journal import Journal
from kb.writer import Commit

GENEROUS = 30.0


@contextmanager
def lock_held_elsewhere(kb: KB) -> Iterator[None]:
    """Another thread holds the KB lock (as a long read does) until the block ends."""
    held, release = threading.Event(), threading.Event()

    def hold() -> None:
        with kb.lock:
            held.set()
            release.wait(GENEROUS)

    holder = threading.Thread(target=hold)
    holder.start()
    try:
        assert held.wait(GENEROUS)
        yield
    finally:
        release.set()
        holder.join()


def test_the_summary_follows_every_change_without_waiting_for_the_lock() -> None:
    with KB() as kb:
        start = kb.summary()
        assert (start.revision, start.models) == (0, ("default",))
        assert start.size == kb.size() and start.asserted == kb.size(inferred=False) > 0
        kb.add(["cup_1 isOn table_1"])
        kb.add(["cup_1 rdf:type Cup"], models=["robot_b"])
        with lock_held_elsewhere(kb):
            now = kb.summary()  # answers while the lock is taken (it would wait forever)
        assert (now.revision, now.models) == (2, ("default", "robot_b"))
        assert (now.size, now.asserted) == (kb.size(), kb.size(inferred=False))
        assert now.asserted == start.asserted + 1
        kb.clear()
        assert (kb.summary().revision, kb.summary().asserted) == (3, start.asserted)


def test_a_refused_commit_leaves_the_summary_as_it_was() -> None:
    with KB() as kb:
        kb.add(["cup_1 isOn table_1"])
        before = kb.summary()

        def refuse(commit: Commit) -> None:
            raise StorageError("the disk is full")

        kb.on_commit(refuse, durable=True)
        with pytest.raises(StorageError):
            kb.add(["cup_2 isOn table_1"], models=["robot_b"])
        assert kb.summary() == before
        with pytest.raises(StorageError):
            kb.clear()
        assert kb.summary() == before


@pytest.mark.parametrize("last", ["write", "clear", "snapshot"])
def test_a_recovered_kb_summarises_what_it_recovered(tmp_path: Path, last: str) -> None:
    with KB() as kb:
        journal = Journal(tmp_path)
        journal.recover(kb)
        kb.add(["cup_1 isOn table_1"])
        kb.add(["cup_1 rdf:type Cup"], models=["robot_b"])
        if last == "clear":
            kb.clear()
        if last == "snapshot":
            journal.snapshot(kb)
        expected = kb.summary()
        journal.close()
    with KB() as again:
        journal = Journal(tmp_path)
        journal.recover(again)
        journal.close()
        assert again.summary().revision == again.revision == expected.revision
        assert (again.summary().size, again.summary().asserted) == (again.size(), again.size(inferred=False))
        assert again.summary().asserted == expected.asserted
