"""``situated data check|repair``'s library: what is intact, what is damaged, and a repair that
keeps the damaged files and recovers every record it can."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from kb import KB
from kb.datadir import check, repair
from kb.journal import JOURNAL, SNAPSHOT, SNAPSHOT_TMP, Journal
from kb.records import frame
from kb.terms import ORO


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


def _write(directory: Path, kbs: list[KB], count: int, snapshot_after: int | None = None) -> None:
    kb, journal = _open(directory, kbs)
    for i in range(count):
        kb += f"s{i} sees o{i}"
        if snapshot_after == i:
            journal.snapshot(kb)
    journal.close()



def test_check_tells_intact_harmless_and_damaged_apart(tmp_path: Path, kbs: list[KB]) -> None:
    _write(tmp_path, kbs, 10, snapshot_after=4)
    report = check(tmp_path)
    assert not report.damaged
    assert "snapshot.json: ok: revision 5" in report.render()
    assert "journal.log: ok: 5 intact record(s), revisions 6..10" in report.render()
    path = tmp_path / JOURNAL
    path.write_bytes(path.read_bytes()[:-5])  # a crash in the middle of the last append
    (tmp_path / SNAPSHOT_TMP).write_bytes(b"{")
    report = check(tmp_path)
    assert not report.damaged
    assert "journal.log: harmless:" in report.render() and "snapshot.json.tmp: harmless" in report.render()


def test_repair_of_a_flipped_byte_keeps_the_original_and_every_intact_record(tmp_path: Path,
                                                                             kbs: list[KB]) -> None:
    _write(tmp_path, kbs, 200)
    path = tmp_path / JOURNAL
    lines = path.read_bytes().splitlines(keepends=True)
    flipped = bytearray(lines[99])
    flipped[20] ^= 0x40
    damaged = b"".join(lines[:99]) + bytes(flipped) + b"".join(lines[100:])
    path.write_bytes(damaged)
    assert check(tmp_path).damaged
    report = repair(tmp_path)
    assert "199 intact record(s)" in report.render()
    originals = list(tmp_path.glob(f"{JOURNAL}.damaged-*"))
    assert len(originals) == 1 and originals[0].read_bytes() == damaged
    # the damaged record's revision is marked lost, so that the journal's revisions follow on
    assert "revisions 100..100 marked lost" in report.render()
    assert path.read_bytes() == b"".join([*lines[:99], frame({"revision": 100, "lost": 100}), *lines[100:]])
    assert not check(tmp_path).damaged
    again, _ = _open(tmp_path, kbs)
    assert {r["s"] for r in again["?s sees ?o"]} == {f"s{i}" for i in range(200) if i != 99}


def test_repair_of_a_snapshot_with_a_bad_checksum_keeps_what_still_reads(tmp_path: Path, kbs: list[KB]) -> None:
    _write(tmp_path, kbs, 6, snapshot_after=5)
    path = tmp_path / SNAPSHOT
    original = path.read_bytes()
    damaged = original.replace(b"#s3>", b"#s3", 1)  # s3's statement no longer parses; still JSON
    path.write_bytes(damaged)
    assert check(tmp_path).damaged
    report = repair(tmp_path)
    assert "1 unreadable statement(s) dropped" in report.render()
    assert next(tmp_path.glob(f"{SNAPSHOT}.damaged-*")).read_bytes() == damaged
    assert not check(tmp_path).damaged
    again, _ = _open(tmp_path, kbs)
    assert {r["s"] for r in again["?s sees ?o"]} == {"s0", "s1", "s2", "s4", "s5"} and again.revision == 6


def test_repair_of_an_unreadable_snapshot_keeps_the_journal(tmp_path: Path, kbs: list[KB]) -> None:
    _write(tmp_path, kbs, 6, snapshot_after=2)
    (tmp_path / SNAPSHOT).write_bytes(b"")
    report = repair(tmp_path)
    assert "could not be read at all" in report.render()
    # the journal starts at revision 4: the lost revisions are said, and marked in a new snapshot
    assert "revisions 1..3 are lost" in report.render() and not check(tmp_path).damaged
    assert next(tmp_path.glob(f"{SNAPSHOT}.damaged-*")).read_bytes() == b""
    again, _ = _open(tmp_path, kbs)
    assert {r["s"] for r in again["?s sees ?o"]} == {"s3", "s4", "s5"}  # what the journal held


def test_repair_of_a_snapshot_cut_short_keeps_every_statement_before_the_cut(tmp_path: Path,
                                                                            kbs: list[KB]) -> None:
    # issue 26, item 7: 100 bytes cut off the snapshot used to drop the whole file
    _write(tmp_path, kbs, 100, snapshot_after=49)
    path = tmp_path / SNAPSHOT
    original = path.read_bytes()
    path.write_bytes(original[:-100])
    assert check(tmp_path).damaged
    # the statements wholly before the cut (a JSON string each, closing quote included)
    whole = {f"s{i}" for i in range(50) if f'#s{i}> <{ORO}sees> <{ORO}o{i}>"'.encode() in original[:-100]}
    assert len(whole) >= 47
    report = repair(tmp_path)
    assert f"rewritten from what still reads (revision 50, {len(whole)} statement(s) kept" in report.render(), \
        report.render()
    assert next(tmp_path.glob(f"{SNAPSHOT}.damaged-*")).read_bytes() == original[:-100]
    assert not check(tmp_path).damaged
    again, _ = _open(tmp_path, kbs)
    assert {r["s"] for r in again["?s sees ?o"]} == whole | {f"s{i}" for i in range(50, 100)}
    assert again.revision == 100


def test_a_journal_that_does_not_continue_the_snapshot_is_damage_until_repaired(tmp_path: Path,
                                                                                kbs: list[KB]) -> None:
    # issue 26, item 7: a deleted snapshot, and a journal that starts at a later revision
    _write(tmp_path, kbs, 100, snapshot_after=49)
    (tmp_path / SNAPSHOT).unlink()
    report = check(tmp_path)
    assert report.damaged
    assert "revisions: damaged: the journal does not continue a snapshot (there is none): its next " \
           "record is revision 51, so revisions 1..50 are in neither" in report.render(), report.render()
    report = repair(tmp_path)
    assert "revisions 1..50 are lost" in report.render()
    assert (tmp_path / JOURNAL).read_bytes().count(b"\n") == 50  # every record kept
    assert not check(tmp_path).damaged
    again, _ = _open(tmp_path, kbs)
    assert {r["s"] for r in again["?s sees ?o"]} == {f"s{i}" for i in range(50, 100)}
    assert again.revision == 100


def test_check_calls_a_flipped_bit_in_the_last_record_damage(tmp_path: Path, kbs: list[KB]) -> None:
    # issue 26, item 6: a complete last record failing its checksum was acknowledged
    _write(tmp_path, kbs, 10)
    path = tmp_path / JOURNAL
    data = bytearray(path.read_bytes())
    data[-20] ^= 0x02
    path.write_bytes(bytes(data))
    report = check(tmp_path)
    assert report.damaged and "journal.log: damaged:" in report.render()
    assert "its last record is complete but does not match its checksum" in report.render()


def test_a_record_removed_mid_journal_is_damage_and_repair_marks_its_revision_lost(tmp_path: Path,
                                                                                 kbs: list[KB]) -> None:
    # issue 26, rerun of attack 6: check said "ok: 29 intact record(s), revisions 1..30"
    _write(tmp_path, kbs, 30, snapshot_after=4)
    path = tmp_path / JOURNAL
    lines = path.read_bytes().splitlines(keepends=True)  # revisions 6..30
    repeated = lines[2]
    path.write_bytes(b"".join(lines[:5] + lines[6:] + [repeated]))  # 11 gone, 8 again at the end
    report = check(tmp_path)
    assert report.damaged, report.render()
    rendered = report.render()
    assert "revisions: damaged: revisions 11..11 are missing between the records of revisions 10 and 12" \
           in rendered and "(revision 8) follows revision 30: repeated or out of order" in rendered, rendered
    report = repair(tmp_path)
    assert "revisions 11..11 marked lost (their records are gone; the service starts without " \
           "them); 1 repeated or out-of-order record(s) left out (revisions 8)" in report.render(), report.render()
    assert not check(tmp_path).damaged, check(tmp_path).render()
    again, _ = _open(tmp_path, kbs)
    assert {r["s"] for r in again["?s sees ?o"]} == {f"s{i}" for i in range(30)} - {"s10"}
    assert again.revision == 30
    again += "later sees more"  # the journal goes on after the marker
    assert again.revision == 31


def test_repair_of_a_snapshot_zeroed_in_the_middle_keeps_the_statements_after_the_damage(
        tmp_path: Path, kbs: list[KB]) -> None:
    # issue 26, rerun of attack 7: repair kept the 29 statements before 512 zero bytes, of 88
    _write(tmp_path, kbs, 100, snapshot_after=87)
    path = tmp_path / SNAPSHOT
    data = bytearray(path.read_bytes())
    third = len(data) // 3
    data[third:third + 512] = bytes(512)
    path.write_bytes(bytes(data))
    intact = {f"s{i}" for i in range(88) if f'"<{ORO}s{i}> <{ORO}sees> <{ORO}o{i}>"'.encode() in data}
    assert len(intact) >= 88 - 7
    report = repair(tmp_path)
    assert f"{len(intact)} statement(s) kept" in report.render() and "read after damaged bytes" in report.render()
    assert not check(tmp_path).damaged
    again, _ = _open(tmp_path, kbs)
    assert {r["s"] for r in again["?s sees ?o"]} == intact | {f"s{i}" for i in range(88, 100)}
