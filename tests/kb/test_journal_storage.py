"""The journal on a real full disk (a 2 MiB tmpfs: see tests/smallfs.py): a refused append
leaves the file and the KB as they were; compaction survives ENOSPC, says so, retries and
leaves no temporary file; a temporary file a crash left is removed at start."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from kb import KB, KbError
from kb.errors import StorageFull
from kb.journal import JOURNAL, SNAPSHOT, SNAPSHOT_TMP, Journal
from kb.records import scan
from tests.smallfs import fill, small_fs
from tests.waiting import until

__all__ = ["small_fs"]


@pytest.fixture
def kbs() -> Iterator[list[KB]]:
    opened: list[KB] = []
    yield opened
    for kb in opened:
        kb.close()


def _open(directory: Path, kbs: list[KB]) -> tuple[KB, Journal]:
    kb = KB()
    kbs.append(kb)
    journal = Journal(directory)
    journal.recover(kb)
    return kb, journal


def test_a_refused_append_leaves_the_journal_and_the_kb_as_they_were(small_fs: Path, kbs: list[KB]) -> None:
    data = small_fs / "data"
    kb, journal = _open(data, kbs)
    kb += "s0 sees o0"
    filler = fill(small_fs)
    acked, refused = ["s0"], ""
    for i in range(1, 200):  # the journal's last page takes a few more records, then one is cut short
        size, revision, state = (data / JOURNAL).stat().st_size, kb.revision, kb.export("nt")
        try:
            kb += f"s{i} sees o{i}"
        except StorageFull as exc:
            refused = f"s{i}"
            assert isinstance(exc, KbError) and "full" in str(exc) and str(data) in str(exc)
            break
        acked.append(f"s{i}")
    assert refused, "the disk never filled up"
    assert (data / JOURNAL).stat().st_size == size  # cut back to the last acknowledged record
    assert kb.revision == revision and kb.export("nt") == state
    found = scan((data / JOURNAL).read_bytes())
    assert not found.damage and found.torn_bytes == 0 and len(found.records) == len(acked)
    status = journal.storage_status()
    assert not status.ok and status.code == "storage_full"
    filler.unlink()
    kb += "after sees it"
    assert journal.storage_status().ok
    assert found.records[-1][2]["revision"] + 1 == kb.revision  # the refused one took no revision
    journal.close()
    again, _ = _open(data, kbs)
    assert {row["s"] for row in again["?s sees ?o"]} == {*acked, "after"}


def test_compaction_survives_a_full_disk_reports_it_and_retries(small_fs: Path, kbs: list[KB]) -> None:
    data = small_fs / "data"
    kb, journal = _open(data, kbs)
    journal.compact_every(kb, records=5, check_seconds=0.05, max_backoff=0.2)
    for i in range(4):
        kb += f"s{i} sees o{i}"
    filler = fill(small_fs)
    kb += "s4 sees o4"  # the fifth record still fits in the journal's last page; a snapshot does not
    until(lambda: journal.compaction.get().failures >= 2), journal.compaction.get()
    status = journal.compaction.get()
    assert status.code == "storage_full" and "compaction failed" in status.reason and status.retry_in
    assert not (data / SNAPSHOT_TMP).exists() and not (data / SNAPSHOT).exists()
    filler.unlink()
    until(lambda: journal.compaction.get().ok), journal.compaction.get()
    assert (data / SNAPSHOT).exists() and (data / JOURNAL).stat().st_size == 0
    assert journal.records_since_snapshot == 0
    kb += "s5 sees o5"
    journal.close()
    again, _ = _open(data, kbs)
    assert len(again["?s sees ?o"]) == 6


def test_a_snapshot_a_crash_cut_short_is_removed_at_start(tmp_path: Path, kbs: list[KB]) -> None:
    kb, journal = _open(tmp_path, kbs)
    kb += "a sees b"
    journal.close()
    (tmp_path / SNAPSHOT_TMP).write_bytes(b'{"revision": 9, "mod')  # a kill during a snapshot
    again, _ = _open(tmp_path, kbs)
    assert not (tmp_path / SNAPSHOT_TMP).exists()
    assert again["a sees ?x"] == [{"x": "b"}]
