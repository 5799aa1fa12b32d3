"""Damaged data, with real processes: ``situated serve --data DIR`` refuses to start on a journal
with a flipped byte mid-file or on a damaged snapshot, with a clear message (no traceback);
``situated data check`` says what is wrong, ``situated data repair`` keeps the damaged file and
every intact record, and the service then starts with them."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import httpx
import pytest

from bench.oxigraph import free_port
from kb import KB
from kb.journal import JOURNAL, SNAPSHOT, Journal
from tests.reliability.server import ServerProcess

ROOT = Path(__file__).parents[2]


def _situated(*args: str, timeout: float = 120) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "api.cli", *args], capture_output=True, text=True,
                          timeout=timeout, cwd=ROOT, check=False)


def _journal_of(directory: Path, count: int, snapshot: bool = False) -> None:
    with KB() as kb:
        journal = Journal(directory)
        journal.recover(kb)
        for i in range(count):
            kb += f"s{i} sees o{i}"
        if snapshot:
            journal.snapshot(kb)
        journal.close()


def _refused_start(data: Path) -> str:
    # Refused before anything listens; a server that started anyway is ended by the timeout.
    try:
        done = _situated("serve", "--data", str(data), "--scene", "none", "--port", str(free_port()),
                         timeout=60)
    except subprocess.TimeoutExpired:
        pytest.fail("the service started on damaged data")
    assert done.returncode == 2, (done.returncode, done.stderr[-2000:])
    assert "Traceback" not in done.stderr
    return done.stderr


def test_a_flipped_byte_mid_journal_stops_the_start_until_repaired(tmp_path: Path) -> None:
    data = tmp_path / "data"
    _journal_of(data, 200)
    path = data / JOURNAL
    lines = path.read_bytes().splitlines(keepends=True)
    flipped = bytearray(lines[99])
    flipped[len(flipped) // 2] ^= 0x04
    damaged = b"".join(lines[:99]) + bytes(flipped) + b"".join(lines[100:])
    path.write_bytes(damaged)

    message = _refused_start(data)
    assert "journal.log is damaged at byte" in message and f"situated data repair {data}" in message
    assert path.read_bytes() == damaged

    checked = _situated("data", "check", str(data))
    assert checked.returncode == 1 and "journal.log: damaged" in checked.stdout, checked.stdout
    repaired = _situated("data", "repair", str(data))
    assert repaired.returncode == 0 and "199 intact record(s)" in repaired.stdout, repaired.stdout
    assert next(data.glob(f"{JOURNAL}.damaged-*")).read_bytes() == damaged

    server = ServerProcess(["--data", str(data), "--scene", "none"], tmp_path / "server.log")
    try:
        server.wait_ready(timeout=120)
        with httpx.Client(base_url=server.url, timeout=30) as client:
            rows = client.post("/kb/query", json={"patterns": ["?s sees ?o"]}).json()
        assert {r["s"] for r in rows} == {f"s{i}" for i in range(200) if i != 99}
    finally:
        server.kill()


@pytest.mark.parametrize("content", [b"", b'{"revision": 4, "mo'], ids=["empty", "cut short"])
def test_a_damaged_snapshot_stops_the_start_with_a_clear_error(tmp_path: Path, content: bytes) -> None:
    data = tmp_path / "data"
    _journal_of(data, 3, snapshot=True)
    (data / SNAPSHOT).write_bytes(content)
    message = _refused_start(data)
    assert "snapshot.json: damaged: cannot be read" in message and "situated data repair" in message


def test_a_flipped_bit_in_the_last_record_stops_the_start_until_repaired(tmp_path: Path) -> None:
    # issue 26, item 6: the last record is complete, so it was acknowledged: damage, not a torn write
    data = tmp_path / "data"
    _journal_of(data, 20)
    path = data / JOURNAL
    damaged = bytearray(path.read_bytes())
    damaged[-30] ^= 0x08
    path.write_bytes(bytes(damaged))

    message = _refused_start(data)
    assert "journal.log: damaged" in message and "does not match its checksum" in message, message
    assert path.read_bytes() == bytes(damaged)
    checked = _situated("data", "check", str(data))
    assert checked.returncode == 1 and "journal.log: damaged" in checked.stdout, checked.stdout
    assert "harmless" not in checked.stdout


def test_a_deleted_snapshot_stops_the_start_and_the_check_says_why(tmp_path: Path) -> None:
    # issue 26, item 7: the journal begins after the snapshot's revision; starting without it
    # would serve half the facts
    data = tmp_path / "data"
    _journal_of(data, 50, snapshot=True)
    with KB() as kb:  # 50 more writes after the snapshot, in the journal
        journal = Journal(data)
        journal.recover(kb)
        for i in range(50, 100):
            kb += f"s{i} sees o{i}"
        journal.close()
    (data / SNAPSHOT).unlink()

    message = _refused_start(data)
    assert "the journal does not continue a snapshot (there is none)" in message, message
    assert "revisions 1..50 are in neither" in message
    checked = _situated("data", "check", str(data))
    assert checked.returncode == 1 and "revisions: damaged" in checked.stdout, checked.stdout
