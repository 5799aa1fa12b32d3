"""A full disk, for real: ``situated serve --data DIR`` with DIR on a 2 MiB tmpfs (see
tests/smallfs.py for why a tmpfs), filled to the last byte while the server runs.

Refused writes must change nothing, in memory or on disk, and consume no revision; the service
says ``507 storage_full`` and ``/health`` says why it is degraded; once space is freed, writes
are acknowledged again, and after a SIGKILL and a restart every acknowledged fact is there and no
refused one is.
"""

from __future__ import annotations

import resource
import signal
from pathlib import Path

import httpx

from tests.reliability.server import ServerProcess
from tests.smallfs import fill, small_fs

__all__ = ["small_fs"]

MAX_ATTEMPTS = 400  # the journal's last page may still take a few records once the disk is full


def _add(client: httpx.Client, subject: str) -> httpx.Response:
    return client.post("/kb/revise", json={"statements": [f"{subject} sees thing_{subject}"], "method": "add"})


def _holds(client: httpx.Client, subject: str) -> bool:
    rows = client.post("/kb/query", json={"patterns": [f"{subject} sees ?o"]}).json()
    return rows == [{"o": f"thing_{subject}"}] if rows else False


def _start(data: Path, log: Path) -> ServerProcess:
    server = ServerProcess(["--data", str(data), "--scene", "none"], log)
    server.wait_ready(timeout=120)
    return server


def _refused(answer: httpx.Response) -> bool:
    return answer.status_code == 507 and answer.json()["code"] == "storage_full"


def test_a_full_disk_refuses_writes_whole_and_loses_no_acknowledged_one(small_fs: Path, tmp_path: Path) -> None:
    data = small_fs / "data"
    log = tmp_path / "server.log"
    acked: list[str] = []
    refused: list[str] = []
    server = _start(data, log)
    try:
        with httpx.Client(base_url=server.url, timeout=30) as client:
            for name in ("before0", "before1"):
                assert _add(client, name).status_code == 200
                acked.append(name)
    finally:
        server.stop()  # a clean stop: a snapshot, and an empty journal
    assert (data / "journal.log").stat().st_size == 0, log.read_text()
    # Phase 1: the disk is full before the server starts, so no write at all fits.
    filler = fill(small_fs)
    server = _start(data, log)
    try:
        with httpx.Client(base_url=server.url, timeout=30) as client:
            revision = client.get("/health").json()["kb"]["revision"]
            for i in range(3):
                answer = _add(client, f"refused{i}")
                assert _refused(answer), answer.text
                assert "full" in answer.json()["message"], answer.text
                refused.append(f"refused{i}")
            health = client.get("/health").json()
            assert health["status"] == "degraded", health
            assert health["kb"]["revision"] == revision  # a refused write consumes no revision
            assert any(r.startswith("storage:") and "full" in r for r in health["reasons"]), health

            cleared = client.post("/kb/clear")
            assert _refused(cleared), cleared.text
            assert all(_holds(client, s) for s in acked), "a refused clear emptied the KB"
            entity = client.put("/scene/entities/box_full", json={"kind": "object", "x": 1.0, "y": 0.0})
            assert _refused(entity), entity.text
            assert not any(e["id"] == "box_full" for e in client.get("/scene").json()["entities"])

            # Phase 2: space for a page of journal, then full again: appends fill the page until
            # one is cut short by the disk (a partial write) and refused.
            filler.unlink()
            assert _add(client, "after0").status_code == 200
            acked.append("after0")
            filler = fill(small_fs)
            answer = None
            for i in range(MAX_ATTEMPTS):
                answer = _add(client, f"page{i}")
                if answer.status_code != 200:
                    refused.append(f"page{i}")
                    break
                acked.append(f"page{i}")
            assert answer is not None and _refused(answer), answer and answer.text
            for i in range(3):
                assert _refused(_add(client, f"later{i}"))
                refused.append(f"later{i}")
            assert client.get("/health").json()["status"] == "degraded"
            assert not any(_holds(client, s) for s in refused)

            filler.unlink()
            assert _add(client, "final").status_code == 200
            acked.append("final")
            health = client.get("/health").json()
            assert health["status"] == "ok", health
            assert health["kb"]["revision"] == revision + len(acked) - 2  # one per acknowledged write
            revision = health["kb"]["revision"]
    finally:
        server.kill()

    server = _start(data, log)
    try:
        with httpx.Client(base_url=server.url, timeout=30) as client:
            missing = [s for s in acked if not _holds(client, s)]
            resurrected = [s for s in refused if _holds(client, s)]
            assert missing == [] and resurrected == [], (missing, resurrected)
            assert client.get("/health").json()["kb"]["revision"] == revision
            assert not any(e["id"] == "box_full" for e in client.get("/scene").json()["entities"])
    finally:
        server.kill()


LIMIT = 2 * 1024 * 1024  # bytes any file of the server may grow to (its log included)


def _file_size_limit() -> None:
    # In the server's process: appends past the limit fail with EFBIG instead of killing it.
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (LIMIT, LIMIT))


def test_a_file_size_limit_refuses_writes_and_health_says_why(tmp_path: Path) -> None:
    # issue 26, item 10: appends refused with EFBIG (a file-size limit: the disk has room) were
    # refused correctly, but /health said ok
    server = ServerProcess(["--data", str(tmp_path / "data"), "--scene", "none"], tmp_path / "server.log",
                           preexec=_file_size_limit)
    try:
        server.wait_ready(timeout=120)
        with httpx.Client(base_url=server.url, timeout=60) as client:
            big = "x" * 200_000
            refused = None
            for n in range(40):  # 200 KB a write: the journal reaches 2 MiB within a dozen
                answer = client.post("/kb/revise", json={"statements": [f'item_{n} comment "{big}"'],
                                                         "method": "add"})
                if answer.status_code != 200:
                    refused = answer
                    break
            assert refused is not None, "the file-size limit was never reached"
            assert (refused.status_code, refused.json()["code"]) == (507, "storage_full"), refused.text
            assert "file-size limit" in refused.json()["message"]
            assert client.post("/kb/query", json={"patterns": [f"item_{n} comment ?c"]}).json() == []
            health = client.get("/health").json()
            assert health["status"] == "degraded", health
            storage = health["components"]["storage"]
            assert not storage["ok"] and storage["code"] == "file_too_large", storage
            assert "file-size limit" in storage["reason"], storage
    finally:
        server.kill()
