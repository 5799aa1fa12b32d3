"""Checking and repairing a data directory (``situated data check|repair DIR``).

``check`` reads the snapshot and every journal record and says what is intact, what a crash
left (a last record cut short, a temporary snapshot: both harmless, handled at start) and what is
damaged (a bad snapshot; bytes that are no intact record, a complete last record that fails its
checksum included; a journal that does not continue the snapshot, or whose records do not follow
each other revision by revision): the service refuses to start on those rather than lose
acknowledged writes. ``repair`` keeps each damaged file beside the new
one (``NAME.damaged-TIMESTAMP``) and writes what can be recovered: every intact journal record,
and from a snapshot whose checksum fails, every statement of it that still reads (of one cut
short, every statement before the cut). Revisions that neither holds any more are then marked
lost, in the snapshot or, where journal records are missing, by a marker record in the journal,
so that the service starts with everything else and says what was lost.
Run it while the service is stopped.
"""

from __future__ import annotations

import os
import shutil
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rdflib import BNode

from kb.errors import KbError, storage_error
from kb.journal import JOURNAL, SNAPSHOT, SNAPSHOT_TMP
from kb.records import (
    Break,
    breaks,
    describe_missing,
    first_revision,
    frame,
    missing_revisions,
    parse_nt,
    read_snapshot,
    scan,
)
from kb.salvage import salvage

#: The finding about the two files together: does the journal continue the snapshot?
REVISIONS = "revisions"


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
    missing = _missing(folder)
    if missing is not None:
        report.findings.append(Finding(REVISIONS, "damaged", missing[1]))
    gaps = _breaks(folder)
    if gaps:
        report.findings.append(Finding(REVISIONS, "damaged", "; ".join(g.describe() for g in gaps) +
                                       "; the service will not start without those writes"))
    return report


def repair(directory: str | Path) -> Report:
    """Repair what ``check`` finds damaged; returns the check before, with what was done."""
    report = check(directory)
    folder = report.directory
    damaged = {f.name for f in report.findings if f.state == "damaged"}
    try:
        if SNAPSHOT in damaged:  # first: the journal is judged against what it ends at
            report.actions.append(_repair_snapshot(folder / SNAPSHOT))
        if JOURNAL in damaged or _breaks(folder):
            report.actions.append(_repair_journal(folder))
        # After those repairs: what the snapshot ends at and the journal starts from.
        missing = _missing(folder)
        if missing is not None:
            report.actions.append(_mark_lost(folder / SNAPSHOT, missing[0]))
    except OSError as exc:  # each file is replaced whole or not at all
        raise storage_error(exc, folder, "the repair") from exc
    return report


def _snapshot_revision(folder: Path) -> int | None:
    """The revision the snapshot ends at (0 without one), None when it cannot be read."""
    path = folder / SNAPSHOT
    if not path.exists():
        return 0
    try:
        revision: int = read_snapshot(path.read_bytes())["revision"]
    except ValueError:  # a damaged snapshot: its own finding says so
        return None
    return revision


def _breaks(folder: Path) -> list[Break]:
    """Where the journal's intact records, after the snapshot, do not follow each other."""
    revision = _snapshot_revision(folder)
    journal = folder / JOURNAL
    if revision is None or not journal.exists():
        return []
    return breaks(revision, scan(journal.read_bytes()).records)


def _missing(folder: Path) -> tuple[range, str] | None:
    """The revisions neither a readable snapshot (or its absence) nor the journal holds, and why."""
    path = folder / SNAPSHOT
    revision = _snapshot_revision(folder)
    if revision is None:
        return None
    journal = folder / JOURNAL
    found = scan(journal.read_bytes() if journal.exists() else b"")
    missing = missing_revisions(revision, (first_revision(r) for _s, _e, r in found.records))
    if missing is None:
        return None
    named = f"the snapshot (revision {revision})" if path.exists() else "a snapshot (there is none)"
    return missing, f"{describe_missing(missing, named)}; the service will not start with part of the state"


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
    salvaged = salvage(path.read_bytes())
    if salvaged is None:
        path.unlink()
        _fsync_dir(path.parent)
        return (f"{SNAPSHOT} could not be read at all: kept as {kept.name} and removed; the KB "
                f"starts from the default ontology plus the journal, and what only the snapshot "
                f"held is lost")
    _replace(path, frame(salvaged.state))
    after = (f"; {salvaged.after_damage} of them read after damaged bytes and kept in the list open "
             f"there (a model boundary inside the damage cannot be seen)") if salvaged.after_damage else ""
    return (f"{SNAPSHOT} rewritten from what still reads (revision {salvaged.state['revision']}, "
            f"{salvaged.kept} statement(s) kept, {salvaged.dropped} unreadable statement(s) dropped"
            f"{after}); the original is kept as {kept.name}")


def _mark_lost(path: Path, missing: range) -> str:
    """Make the snapshot (an empty one if there is none) end where the journal starts: the
    missing revisions are gone, everything else is kept."""
    if path.exists():
        kept = _keep(path)
        state = read_snapshot(path.read_bytes())
        where = f"{SNAPSHOT} (kept as {kept.name})"
    else:
        state = {"models": {}, "expiries": []}
        where = f"an empty {SNAPSHOT}"
    state["revision"] = missing.stop - 1
    _replace(path, frame(state))
    return (f"revisions {missing.start}..{missing.stop - 1} are lost (in neither the snapshot nor the "
            f"journal): {where} now ends at revision {missing.stop - 1}, where the journal starts")


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


def _repair_journal(folder: Path) -> str:
    """Rewrite the journal with its intact records in order: a marker of lost revisions (a record
    that changes nothing) where records are missing, and without the damaged bytes and the records
    that repeat or go back on a revision."""
    path = folder / JOURNAL
    data = path.read_bytes()
    found = scan(data)
    kept = _keep(path)
    at = {gap.at: gap for gap in breaks(_snapshot_revision(folder) or 0, found.records)}
    lines: list[bytes] = []
    lost: list[str] = []
    dropped: list[int] = []
    for start, end, record in found.records:
        gap = at.get(start)
        if gap is not None and gap.found <= gap.after:
            dropped.append(record["revision"])
            continue
        if gap is not None:
            lines.append(frame({"revision": gap.found - 1, "lost": gap.after + 1}))
            lost.append(f"{gap.after + 1}..{gap.found - 1}")
        lines.append(data[start:end].rstrip(b"\n") + b"\n")
    _replace(path, b"".join(lines))
    damaged = sum(d.end - d.start for d in found.damage) + found.torn_bytes
    said = [f"{JOURNAL} rewritten with its {len(found.records) - len(dropped)} intact record(s) "
            f"({damaged} damaged bytes left out)"]
    if lost:
        said.append(f"revisions {', '.join(lost)} marked lost (their records are gone; the service "
                    "starts without them)")
    if dropped:
        said.append(f"{len(dropped)} repeated or out-of-order record(s) left out (revisions "
                    f"{', '.join(map(str, dropped))})")
    return f"{'; '.join(said)}; the original is kept as {kept.name}"


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
