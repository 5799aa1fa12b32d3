"""Checking and repairing a data directory (``situated data check|repair DIR``).

``check`` reads the snapshot and every journal record and says what is intact, what a crash
left (a torn last record, a temporary snapshot: both harmless, handled at start) and what is
damaged (a bad snapshot, or bad bytes with intact records after them: the service refuses to
start on those rather than lose acknowledged writes). ``repair`` keeps each damaged file beside
the new one (``NAME.damaged-TIMESTAMP``) and writes what can be recovered: every intact journal
record, and from a snapshot whose checksum fails but whose content still reads, every statement
that parses. Run it while the service is stopped.
"""

from __future__ import annotations

import json
import os
import shutil
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rdflib import BNode

from kb.errors import KbError, storage_error
from kb.journal import JOURNAL, SNAPSHOT, SNAPSHOT_TMP
from kb.records import frame, parse_nt, read_snapshot, scan


@dataclass
class Finding:
    """One file: ``ok``, ``absent``, ``harmless`` (handled at start) or ``damaged``."""

    name: str
    state: str
    detail: str


@dataclass
class Report:
    directory: Path
    findings: list[Finding] = field(default_factory=list)
    actions: list[str] = field(default_factory=list)

    @property
    def damaged(self) -> bool:
        return any(f.state == "damaged" for f in self.findings)

    def render(self) -> str:
        lines = [f"data directory {self.directory}:"]
        lines += [f"  {f.name}: {f.state}: {f.detail}" for f in self.findings]
        lines += [f"  repaired: {a}" for a in self.actions]
        if self.damaged and not self.actions:
            lines.append(f"  the service will not start on it; 'situated data repair {self.directory}' "
                         "keeps every intact record and the damaged files beside them")
        return "\n".join(lines)


def check(directory: str | Path) -> Report:
    folder = Path(directory)
    if not folder.is_dir():
        raise KbError(f"{folder} is not a directory")
    report = Report(folder)
    report.findings.append(_check_snapshot(folder / SNAPSHOT))
    if (folder / SNAPSHOT_TMP).exists():
        report.findings.append(Finding(SNAPSHOT_TMP, "harmless", "left by an interrupted snapshot; "
                                                                 "removed at the next start"))
    report.findings.append(_check_journal(folder / JOURNAL))
    return report


def repair(directory: str | Path) -> Report:
    """Repair what ``check`` finds damaged; returns the check before, with what was done."""
    report = check(directory)
    folder = report.directory
    repairs = {SNAPSHOT: _repair_snapshot, JOURNAL: _repair_journal}
    for finding in report.findings:
        if finding.state == "damaged":
            try:
                report.actions.append(repairs[finding.name](folder / finding.name))
            except OSError as exc:  # each file is replaced whole or not at all
                raise storage_error(exc, folder, f"the repair of {finding.name}") from exc
    return report


# --- the snapshot ------------------------------------------------------------------------------


def _check_snapshot(path: Path) -> Finding:
    if not path.exists():
        return Finding(SNAPSHOT, "absent", "no snapshot yet; the journal holds every write")
    try:
        state = read_snapshot(path.read_bytes())
        statements = _statements(state)
        bnodes: dict[str, BNode] = {}
        for statement in statements:
            parse_nt(statement, bnodes)
    except (ValueError, KeyError, TypeError, KbError) as exc:
        return Finding(SNAPSHOT, "damaged", f"cannot be read ({exc})")
    return Finding(SNAPSHOT, "ok", f"revision {state['revision']}, {len(state['models'])} model(s), "
                                   f"{len(statements)} statement(s)")


def _statements(state: dict[str, Any]) -> list[str]:
    found = [s for change in state["models"].values() for key in ("add", "remove") for s in change[key]]
    return found + [statement for _model, statement, _at in state.get("expiries", [])]


def _repair_snapshot(path: Path) -> str:
    kept = _keep(path)
    salvaged = _salvage(path.read_bytes())
    if salvaged is None:
        path.unlink()
        _fsync_dir(path.parent)
        return (f"{SNAPSHOT} could not be read at all: kept as {kept.name} and removed; the KB "
                f"starts from the default ontology plus the journal, and what only the snapshot "
                f"held is lost")
    state, dropped = salvaged
    _replace(path, frame(state))
    return (f"{SNAPSHOT} rewritten from what still reads (revision {state['revision']}, "
            f"{dropped} unreadable statement(s) dropped); the original is kept as {kept.name}")


def _salvage(data: bytes) -> tuple[dict[str, Any], int] | None:
    """The state of a snapshot whose checksum failed, with its unparsable statements dropped."""
    text = data.strip()
    if not text.startswith(b"{"):
        text = text.split(b" ", 2)[-1]  # the body after ``<length> <crc32>``
    try:
        raw = json.loads(text)
        models = raw["models"]
        revision = raw.get("revision")
        state: dict[str, Any] = {"revision": revision if isinstance(revision, int) else 0, "models": {},
                                 "expiries": []}
        dropped = 0
        bnodes: dict[str, BNode] = {}
        for name, change in models.items():
            kept_change: dict[str, list[str]] = {}
            for key in ("add", "remove"):
                good = [s for s in change.get(key, []) if _parses(s, bnodes)]
                dropped += len(change.get(key, [])) - len(good)
                kept_change[key] = good
            state["models"][str(name)] = kept_change
        for entry in raw.get("expiries", []):
            if _parses(entry[1], bnodes):
                state["expiries"].append(entry)
            else:
                dropped += 1
    except (ValueError, KeyError, TypeError, AttributeError, IndexError):
        return None
    return state, dropped


def _parses(statement: Any, bnodes: dict[str, BNode]) -> bool:
    try:
        parse_nt(str(statement), bnodes)
    except KbError:
        return False
    return isinstance(statement, str)


# --- the journal -------------------------------------------------------------------------------


def _check_journal(path: Path) -> Finding:
    if not path.exists():
        return Finding(JOURNAL, "absent", "no journal yet")
    found = scan(path.read_bytes())
    revisions = [r["revision"] for _s, _e, r in found.records]
    span = f", revisions {revisions[0]}..{revisions[-1]}" if revisions else ""
    intact = f"{len(found.records)} intact record(s){span}"
    if found.damage:
        return Finding(JOURNAL, "damaged", f"{found.describe_damage(JOURNAL)}; {intact}")
    if found.torn_bytes:
        return Finding(JOURNAL, "harmless", f"{intact}; an incomplete last record ({found.torn_bytes} "
                                            f"bytes, never acknowledged) is dropped at the next start")
    return Finding(JOURNAL, "ok", intact)


def _repair_journal(path: Path) -> str:
    data = path.read_bytes()
    found = scan(data)
    kept = _keep(path)
    _replace(path, b"".join(data[start:end] for start, end, _record in found.records))
    lost = sum(d.end - d.start for d in found.damage) + found.torn_bytes
    return (f"{JOURNAL} rewritten with its {len(found.records)} intact record(s) ({lost} damaged bytes "
            f"left out); the original is kept as {kept.name}")


# --- files -------------------------------------------------------------------------------------


def _keep(path: Path) -> Path:
    """A durable copy of ``path`` beside it, named after the time of the repair."""
    stamp = time.strftime("%Y%m%dT%H%M%S")
    copy = path.with_name(f"{path.name}.damaged-{stamp}")
    n = 1
    while copy.exists():
        copy = path.with_name(f"{path.name}.damaged-{stamp}-{n}")
        n += 1
    shutil.copyfile(path, copy)
    with copy.open("rb+") as handle:
        os.fsync(handle.fileno())
    return copy


def _replace(path: Path, data: bytes) -> None:
    tmp = path.with_name(path.name + ".repair")
    with tmp.open("wb") as handle:
        handle.write(data)
        handle.flush()
        os.fsync(handle.fileno())
    os.replace(tmp, path)
    _fsync_dir(path.parent)


def _fsync_dir(directory: Path) -> None:
    fd = os.open(directory, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)
