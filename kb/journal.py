"""A crash-safe KB: an append-only journal of asserted changes, snapshots, and recovery.

Every commit becomes one journal record, written and fsync'd before the write call returns, so
an acknowledged write survives a crash. A record is ``<length> <crc32> <json>\\n``; a torn last
record (short, or with a bad checksum) is detected at start, dropped and cut off, never applied
in part. ``snapshot()`` writes the whole asserted state (as differences from the default
ontology, with lifespans) to a new file, renames it into place and starts an empty journal.
Inferred triples are never stored: recovery replays asserted changes and the reasoner derives
the rest. Lifespans are wall-clock expiry times, so they keep running across restarts.
"""

from __future__ import annotations

import json
import os
import threading
import zlib
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any, BinaryIO

from rdflib import BNode, Literal, URIRef

from kb.errors import KbError
from kb.kb import KB
from kb.terms import Node, Token, Triple, parse_literal, parse_name, tokenize
from kb.writer import Commit

JOURNAL = "journal.log"
SNAPSHOT = "snapshot.json"


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
        self._file: BinaryIO | None = None
        self.records_since_snapshot = 0
        self._stop = threading.Event()
        self._compactor: threading.Thread | None = None

    # --- recovery --------------------------------------------------------------------------

    def recover(self, kb: KB) -> Recovery:
        """Load the snapshot and replay the journal into a fresh KB, then start journaling it."""
        result = Recovery()
        snapshot = self.directory / SNAPSHOT
        if snapshot.exists():
            result.revision = _restore_snapshot(kb, json.loads(snapshot.read_text(encoding="utf-8")))
        path = self.directory / JOURNAL
        good = 0
        if path.exists():
            data = path.read_bytes()
            for end, record in _records(data):
                if record["revision"] > result.revision:
                    _replay(kb, record)
                    result.revision = record["revision"]
                    result.records += 1
                good = end
            result.dropped_bytes = len(data) - good
            if result.dropped_bytes:
                with path.open("r+b") as handle:
                    handle.truncate(good)
                    _fsync(handle)
        self.records_since_snapshot = result.records
        self._file = path.open("ab")
        kb.on_commit(self.append)
        return result

    # --- writing ---------------------------------------------------------------------------

    def append(self, commit: Commit) -> None:
        """Write one commit durably (called under the KB lock, before the write returns)."""
        record: dict[str, Any] = {"revision": commit.revision}
        if commit.cleared is not None:
            record["clear"] = {"keep_defaults": commit.cleared}
        changes = [
            {"model": d.model, "add": [_nt(t) for t in d.asserted_added],
             "remove": [_nt(t) for t in d.asserted_removed]}
            for d in commit.deltas if d.asserted_added or d.asserted_removed
        ]
        if changes:
            record["changes"] = changes
        if commit.expiries:
            record["expiries"] = [[m, _nt(t), at] for m, t, at in commit.expiries]
        line = _frame(json.dumps(record, separators=(",", ":")))
        with self._lock:
            if self._file is None:
                raise KbError("the journal is not open: call recover() first")
            self._file.write(line)
            _fsync(self._file)
            self.records_since_snapshot += 1

    def snapshot(self, kb: KB) -> None:
        """Write the whole asserted state and start a new, empty journal."""
        with kb.lock, self._lock:
            state = kb.writer.state()
            data = {
                "revision": state.revision,
                "models": {
                    name: {"add": [_nt(t) for t in state.extra[name]],
                           "remove": [_nt(t) for t in state.missing.get(name, [])]}
                    for name in state.extra
                },
                "expiries": [[m, _nt(t), at] for m, t, at in state.expiries],
            }
            tmp = self.directory / (SNAPSHOT + ".tmp")
            with tmp.open("wb") as handle:
                handle.write(json.dumps(data).encode())
                _fsync(handle)
            os.replace(tmp, self.directory / SNAPSHOT)
            _fsync_dir(self.directory)
            if self._file is not None:
                self._file.close()
            self._file = (self.directory / JOURNAL).open("wb")
            _fsync(self._file)
            self.records_since_snapshot = 0

    def compact_every(self, kb: KB, records: int, check_seconds: float = 5.0) -> None:
        """Snapshot in the background whenever ``records`` journal records have accumulated, so a
        steady perception stream neither grows the journal nor the replay at start without bound."""
        if records <= 0 or self._compactor is not None:
            return

        def loop() -> None:
            while not self._stop.wait(check_seconds):
                if self.records_since_snapshot >= records and self._file is not None:
                    self.snapshot(kb)

        self._compactor = threading.Thread(target=loop, name="kb-journal-compaction", daemon=True)
        self._compactor.start()

    def close(self) -> None:
        self._stop.set()
        if self._compactor is not None:
            self._compactor.join(timeout=5.0)
            self._compactor = None
        with self._lock:
            if self._file is not None:
                self._file.close()
                self._file = None


# --- records ---------------------------------------------------------------------------------


def _frame(payload: str) -> bytes:
    body = payload.encode()
    return b"%d %08x " % (len(body), zlib.crc32(body)) + body + b"\n"


def _records(data: bytes) -> Iterator[tuple[int, dict[str, Any]]]:
    """Complete, intact records with the offset where each ends; stops at the first bad one."""
    pos = 0
    while pos < len(data):
        head_end = data.find(b" ", pos)
        crc_end = data.find(b" ", head_end + 1) if head_end >= 0 else -1
        if crc_end < 0:
            return
        try:
            length, crc = int(data[pos:head_end]), int(data[head_end + 1 : crc_end], 16)
        except ValueError:
            return
        body = data[crc_end + 1 : crc_end + 1 + length]
        end = crc_end + 1 + length + 1
        if len(body) != length or data[end - 1 : end] != b"\n" or zlib.crc32(body) != crc:
            return
        yield end, json.loads(body)
        pos = end


def _replay(kb: KB, record: dict[str, Any]) -> None:
    revision = record["revision"]
    if "clear" in record:
        kb.writer.clear(record["clear"]["keep_defaults"])
    bnodes: dict[str, BNode] = {}
    expiries: dict[str, list[tuple[Triple, float]]] = {}
    for model, statement, at in record.get("expiries", []):
        expiries.setdefault(model, []).append((_parse_nt(statement, bnodes), at))
    changes = {c["model"]: c for c in record.get("changes", [])}
    for model in sorted(set(changes) | set(expiries)):
        change = changes.get(model, {})
        kb.writer.restore(
            model,
            add=[_parse_nt(s, bnodes) for s in change.get("add", [])],
            remove=[_parse_nt(s, bnodes) for s in change.get("remove", [])],
            expiries=expiries.get(model, []),
            revision=revision,
        )
    kb.writer.revision = revision


def _restore_snapshot(kb: KB, data: dict[str, Any]) -> int:
    bnodes: dict[str, BNode] = {}
    expiries: dict[str, list[tuple[Triple, float]]] = {}
    for model, statement, at in data.get("expiries", []):
        expiries.setdefault(model, []).append((_parse_nt(statement, bnodes), at))
    for model, change in data["models"].items():
        kb.writer.restore(
            model,
            add=[_parse_nt(s, bnodes) for s in change["add"]],
            remove=[_parse_nt(s, bnodes) for s in change["remove"]],
            expiries=expiries.get(model, []),
            revision=data["revision"],
        )
    kb.writer.revision = data["revision"]
    return int(data["revision"])


# --- N-Triples terms (blank nodes included, unlike the KB's statement syntax) -----------------


def _nt(triple: Triple) -> str:
    return " ".join(_nt_term(t) for t in triple)


def _nt_term(term: Node) -> str:
    if isinstance(term, URIRef):
        return f"<{term}>"
    if isinstance(term, BNode):
        return f"_:{term}"
    body = json.dumps(str(term), ensure_ascii=False)  # a JSON string is a valid N-Triples string
    if term.language:
        return f"{body}@{term.language}"
    if term.datatype is not None:
        return f"{body}^^<{term.datatype}>"
    return body


def _parse_nt(statement: str, bnodes: dict[str, BNode]) -> Triple:
    tokens = tokenize(statement)
    if len(tokens) != 3:
        raise KbError(f"corrupt journal statement {statement!r}")
    return (_node(tokens[0], bnodes), _node(tokens[1], bnodes), _node(tokens[2], bnodes))


def _node(token: Token, bnodes: dict[str, BNode]) -> Node:
    if token.literal:
        lit: Literal = parse_literal(token.text)
        return lit
    if token.text.startswith("_:"):
        label = token.text[2:]
        return bnodes.setdefault(label, BNode(label))
    return parse_name(token.text, "journal")


def _fsync(handle: BinaryIO) -> None:
    handle.flush()
    os.fsync(handle.fileno())


def _fsync_dir(directory: Path) -> None:
    fd = os.open(directory, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)
