"""A crash-safe KB: an append-only journal of asserted changes, snapshots, and recovery.

Every commit becomes one journal record, written and fsync'd before the write call returns, so
an acknowledged write survives a crash. A write the disk refuses (full, I/O error) is cut off
again, so the file ends at the last acknowledged record, and the commit is undone in memory: a
refused write changes nothing and consumes no revision. Records carry a checksum
(``kb.records``); at start a last record cut short (a torn append) is dropped, while any other
damage, a complete last record that fails its checksum included, stops the start
(``DataCorrupt``), since going on would silently lose acknowledged writes:
``situated data check|repair DIR`` (``kb.datadir``) deals with it. ``snapshot()`` writes the
whole asserted state (as differences from the default ontology, with lifespans) to a new file,
renames it into place and starts an empty journal; background compaction survives its errors,
retries with backoff and reports them in ``compaction`` (a ``StatusCell``), as appends do in
``storage``. Inferred triples are never stored: recovery replays asserted changes and the
reasoner derives the rest. Lifespans are wall-clock expiry times, so they keep running across
restarts.
"""

from __future__ import annotations

import errno
import logging
import os
import shutil
import threading
from dataclasses import dataclass
from pathlib import Path
from typing import Any, BinaryIO

from rdflib import BNode

from kb.errors import DataCorrupt, KbError, StorageError, StorageFull, storage_error
from kb.kb import KB
from kb.records import (
    breaks,
    describe_missing,
    first_revision,
    frame,
    missing_revisions,
    nt,
    parse_nt,
    read_snapshot,
    scan,
)
from kb.status import ComponentStatus, StatusCell
from kb.terms import Triple
from kb.writer import Commit

log = logging.getLogger(__name__)

JOURNAL = "journal.log"
SNAPSHOT = "snapshot.json"
SNAPSHOT_TMP = SNAPSHOT + ".tmp"
LOW_SPACE = 256 * 1024  # bytes free under which storage is reported degraded before writes fail
MAX_BACKOFF = 300.0  # seconds between compaction attempts that keep failing
REPLAY_BATCH = 200_000  # changed statements replayed (and reasoned) at once at most


def repair_hint(directory: Path) -> str:
    return (f"run 'situated data check {directory}' to see what is damaged, and 'situated data "
            f"repair {directory}' to keep every intact record (the damaged files are kept beside them)")


@dataclass
class Recovery:
    """What recovery found: the revision reached, records replayed, and any torn tail dropped."""

    revision: int = 0
    records: int = 0
    dropped_bytes: int = 0


class Journal:
    """The durable log of one KB's asserted changes in ``directory``."""

    def __init__(self, directory: str | Path) -> None:
        self.directory = Path(directory)
        self.directory.mkdir(parents=True, exist_ok=True)
        self._lock = threading.Lock()
        self._fd: int | None = None
        self._size = 0  # bytes of acknowledged records in the journal file
        self._dirty = False  # a refused append may have left bytes past _size
        self.records_since_snapshot = 0
        self.storage = StatusCell()
        self.compaction = StatusCell()
        self._stop = threading.Event()
        self._compactor: threading.Thread | None = None

    # --- recovery --------------------------------------------------------------------------

    def recover(self, kb: KB) -> Recovery:
        """Load the snapshot and replay the journal into a fresh KB, then start journaling it.
        ``DataCorrupt`` if the snapshot or a record before the journal's end is damaged.

        The KB lock is held until the journal takes the KB's commits: the expiry thread that
        restored lifespans start would otherwise retract what ran out meanwhile unjournaled,
        and the next replay would bring back the old expiry time of a fact acknowledged again."""
        (self.directory / SNAPSHOT_TMP).unlink(missing_ok=True)  # a snapshot a crash cut short
        with kb.lock:
            result = self._replay_into(kb)
            self.records_since_snapshot = result.records
            self._fd = os.open(self.directory / JOURNAL, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
            self._size = os.fstat(self._fd).st_size
            kb.on_commit(self.append, durable=True)
        return result

    def _replay_into(self, kb: KB) -> Recovery:
        result = Recovery()
        snapshot = self.directory / SNAPSHOT
        path = self.directory / JOURNAL
        found = scan(path.read_bytes() if path.exists() else b"")
        if found.damage:
            raise DataCorrupt(f"{found.describe_damage(str(path))}; not starting, since that would "
                              f"lose acknowledged writes: {repair_hint(self.directory)}")
        state: dict[str, Any] | None = None
        if snapshot.exists():
            try:
                state = read_snapshot(snapshot.read_bytes())
            except ValueError as exc:
                raise DataCorrupt(f"{snapshot} cannot be read ({exc}); not starting without the "
                                  f"state it holds: {repair_hint(self.directory)}") from exc
        since = state["revision"] if state else 0
        missing = missing_revisions(since, (first_revision(record) for _s, _e, record in found.records))
        if missing is not None:
            named = f"the snapshot {snapshot} (revision {missing.start - 1})" if state else \
                f"a snapshot (there is none: {snapshot} is missing)"
            raise DataCorrupt(f"{describe_missing(missing, named)}; not starting with part of the "
                              f"state: {repair_hint(self.directory)}")
        gaps = breaks(since, found.records)
        if gaps:
            raise DataCorrupt(f"{path}: {gaps[0].describe()} ({len(gaps)} such place(s)); not starting "
                              f"without acknowledged writes: {repair_hint(self.directory)}")
        if state is not None:
            try:
                result.revision = _restore_snapshot(kb, state)
            except (KeyError, TypeError, KbError) as exc:
                raise DataCorrupt(f"{snapshot} cannot be read ({exc}); not starting without the "
                                  f"state it holds: {repair_hint(self.directory)}") from exc
        if not path.exists():
            return result
        replay = _Replay(kb)
        for _start, _end, record in found.records:
            if record["revision"] > result.revision:
                replay.record(record)
                result.revision = record["revision"]
                result.records += 1
        replay.flush()
        result.dropped_bytes = found.torn_bytes
        if found.torn_bytes or found.unterminated:
            with path.open("r+b") as handle:
                handle.truncate(found.torn_at)
                if found.unterminated:  # the next record starts on a line of its own
                    handle.seek(found.torn_at)
                    handle.write(b"\n")
                _fsync(handle)
        return result

    # --- writing ---------------------------------------------------------------------------

    def append(self, commit: Commit) -> None:
        """Write one commit durably (called under the KB lock, before the write returns). On an
        OS error the file is cut back to its last acknowledged record and ``StorageError``
        (``StorageFull`` for a full disk) raised, so the KB undoes the commit."""
        line = frame(_record(commit))
        with self._lock:
            if self._fd is None:
                raise KbError("the journal is not open: call recover() first")
            try:
                if self._dirty:
                    self._cut_back()
                _write_all(self._fd, line)
                os.fsync(self._fd)
            except OSError as exc:
                self._dirty = True
                self._try_cut_back()
                error = storage_error(exc, self.directory, "the write")
                self.storage.failed(_code(error), str(error))
                raise error from exc
            self._size += len(line)
            self.records_since_snapshot += 1
        self.storage.succeeded()

    def _cut_back(self) -> None:
        """Remove what a refused append left after the last acknowledged record."""
        assert self._fd is not None
        os.ftruncate(self._fd, self._size)
        os.fsync(self._fd)
        self._dirty = False

    def _try_cut_back(self) -> None:
        try:
            self._cut_back()
        except OSError:  # the next append tries again before writing, and refuses if it cannot
            log.exception("could not cut the journal back to its last acknowledged record")

    def storage_status(self) -> ComponentStatus:
        """The journal's disk: degraded while writes fail for want of space (until space is
        free again) or for another I/O error, a file at its size limit (EFBIG) included (until one
        succeeds: free disk space says nothing of that limit), or while space runs low."""
        status = self.storage.get()
        free = _free_bytes(self.directory)
        if not status.ok and (status.code != "storage_full" or free is None or free < LOW_SPACE):
            return status
        if free is not None and free < LOW_SPACE:
            return ComponentStatus(ok=False, code="storage_low",
                                   reason=f"the disk of the data directory {self.directory} has "
                                          f"{free} bytes free; writes fail when it is full")
        return ComponentStatus()

    def snapshot(self, kb: KB) -> None:
        """Write the whole asserted state and start a new, empty journal. ``StorageError`` if
        the snapshot cannot be written; the journal is then left as it was."""
        with kb.lock, self._lock:
            state = kb.writer.state()
            data = {
                "revision": state.revision,
                "models": {
                    name: {"add": [nt(t) for t in state.extra[name]],
                           "remove": [nt(t) for t in state.missing.get(name, [])]}
                    for name in state.extra
                },
                "expiries": [[m, nt(t), at] for m, t, at in state.expiries],
            }
            tmp = self.directory / SNAPSHOT_TMP
            try:
                with tmp.open("wb") as handle:
                    handle.write(frame(data))
                    _fsync(handle)
                os.replace(tmp, self.directory / SNAPSHOT)
                _fsync_dir(self.directory)
            except OSError as exc:
                tmp.unlink(missing_ok=True)
                raise storage_error(exc, self.directory, "the snapshot") from exc
            self.records_since_snapshot = 0
            if self._fd is not None:  # the snapshot holds every record: the journal starts over
                try:
                    os.ftruncate(self._fd, 0)
                    os.fsync(self._fd)
                    self._size, self._dirty = 0, False
                except OSError:  # harmless: replay skips records the snapshot already holds
                    log.exception("the snapshot is written but the journal could not be emptied")

    def compact_every(self, kb: KB, records: int, check_seconds: float = 5.0,
                      max_backoff: float = MAX_BACKOFF) -> None:
        """Snapshot in the background whenever ``records`` journal records have accumulated, so a
        steady perception stream neither grows the journal nor the replay at start without bound.
        A snapshot that fails is retried after a growing delay (up to ``max_backoff``) and
        reported in ``compaction`` until one succeeds."""
        if records <= 0 or self._compactor is not None:
            return

        def loop() -> None:
            delay = check_seconds
            while not self._stop.wait(delay):
                delay = check_seconds
                if self.records_since_snapshot < records or self._fd is None:
                    continue
                try:
                    self.snapshot(kb)
                except StorageError as exc:
                    delay = min(max_backoff, check_seconds * 2 ** (self.compaction.get().failures + 1))
                    self.compaction.failed(_code(exc), f"compaction failed: {exc}; retrying in "
                                                       f"{delay:g} s", retry_in=delay)
                    log.warning("journal compaction failed, retrying in %g s: %s", delay, exc)
                else:
                    self.compaction.succeeded()

        self._compactor = threading.Thread(target=loop, name="kb-journal-compaction", daemon=True)
        self._compactor.start()

    def close(self) -> None:
        self._stop.set()
        if self._compactor is not None:
            self._compactor.join(timeout=5.0)
            self._compactor = None
        with self._lock:
            if self._fd is not None:
                os.close(self._fd)
                self._fd = None


def _record(commit: Commit) -> dict[str, Any]:
    record: dict[str, Any] = {"revision": commit.revision}
    if commit.cleared is not None:
        record["clear"] = {"keep_defaults": commit.cleared}
    changes = [
        {"model": d.model, "add": [nt(t) for t in d.asserted_added],
         "remove": [nt(t) for t in d.asserted_removed]}
        for d in commit.deltas if d.asserted_added or d.asserted_removed
    ]
    if changes:
        record["changes"] = changes
    if commit.expiries:
        record["expiries"] = [[m, nt(t), at] for m, t, at in commit.expiries]
    return record


def _code(error: StorageError) -> str:
    if error.errno == errno.EFBIG:
        return "file_too_large"
    return "storage_full" if isinstance(error, StorageFull) else "storage_error"


def _write_all(fd: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view):]


def _free_bytes(directory: Path) -> int | None:
    try:
        return shutil.disk_usage(directory).free
    except OSError:
        return None


class _Replay:
    """Journal records replayed in batches, each reasoned once: per model, the last change of each
    triple (retracted, or asserted) since the last flush, which leaves the asserted triples as the
    records did one by one, so the closure too. A perception stream journals thousands of small
    records that add and retract the same facts; one by one, each paid its own reasoning. Lifespans
    are replayed record by record (their last word counts); a clear flushes first."""

    def __init__(self, kb: KB) -> None:
        self.kb = kb
        self._last: dict[str, dict[Triple, bool]] = {}  # model -> triple -> asserted at the end
        self._pending = 0
        self._revision = 0

    def record(self, record: dict[str, Any]) -> None:
        revision = record["revision"]
        if "clear" in record:
            self.flush()
            self.kb.writer.clear(record["clear"]["keep_defaults"])
        bnodes: dict[str, BNode] = {}
        expiries: dict[str, list[tuple[Triple, float]]] = {}
        for model, statement, at in record.get("expiries", []):
            expiries.setdefault(model, []).append((parse_nt(statement, bnodes), at))
        changes = {c["model"]: c for c in record.get("changes", [])}
        for model in sorted(set(changes) | set(expiries)):
            change = changes.get(model, {})
            last = self._last.setdefault(model, {})
            removed = [parse_nt(s, bnodes) for s in change.get("remove", [])]
            for triple in removed:  # retracted first, then asserted, as the commit did
                last[triple] = False
            for statement in change.get("add", []):
                last[parse_nt(statement, bnodes)] = True
            self._pending += len(removed) + len(change.get("add", []))
            # The model exists from this record on, and lifespans change in record order.
            ended = [(t, 0.0) for t in removed] if len(self.kb.writer.expiries) else []
            self.kb.writer.restore(model, [], [], ended + expiries.get(model, []), revision=revision)
        self._revision = revision
        self.kb.writer.revision = revision
        if self._pending >= REPLAY_BATCH:
            self.flush()

    def flush(self) -> None:
        for model, last in self._last.items():
            add = [t for t, asserted in last.items() if asserted]
            remove = [t for t, asserted in last.items() if not asserted]
            self.kb.writer.restore(model, add, remove, [], revision=self._revision)
        self._last, self._pending = {}, 0


def _restore_snapshot(kb: KB, data: dict[str, Any]) -> int:
    bnodes: dict[str, BNode] = {}
    expiries: dict[str, list[tuple[Triple, float]]] = {}
    for model, statement, at in data.get("expiries", []):
        expiries.setdefault(model, []).append((parse_nt(statement, bnodes), at))
    for model, change in data["models"].items():
        kb.writer.restore(
            model,
            add=[parse_nt(s, bnodes) for s in change["add"]],
            remove=[parse_nt(s, bnodes) for s in change["remove"]],
            expiries=expiries.get(model, []),
            revision=data["revision"],
        )
    kb.writer.revision = data["revision"]
    return int(data["revision"])


def _fsync(handle: BinaryIO) -> None:
    handle.flush()
    os.fsync(handle.fileno())


def _fsync_dir(directory: Path) -> None:
    fd = os.open(directory, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)
