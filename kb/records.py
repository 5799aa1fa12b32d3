"""The data directory's formats: checksummed records, the scan that tells a torn tail from
corruption, and N-Triples terms (blank nodes included, unlike the KB's statement syntax).

A record is one line, ``<length> <crc32> <json>\\n`` (compact JSON never holds a raw newline).
The journal is a sequence of records; the snapshot is one record (older snapshots were bare
JSON, still read). A scan reads every line. Only a record cut short is a torn tail, what a crash
in the middle of an append leaves: an append writes the newline last and a record never holds
one, so a torn record is the file's last bytes, with no newline and fewer bytes than its header
announces. Anything else that is not an intact record is damage, the last record included: a
complete record that fails its checksum was acknowledged, and starting without it would lose it.
"""

from __future__ import annotations

import json
import re
import zlib
from collections.abc import Iterable
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

from rdflib import BNode, Literal, URIRef

from kb.errors import KbError
from kb.terms import Node, Token, Triple, parse_literal, parse_name, tokenize


def frame(payload: dict[str, Any]) -> bytes:
    body = json.dumps(payload, separators=(",", ":")).encode()
    return b"%d %08x " % (len(body), zlib.crc32(body)) + body + b"\n"


# What an append has written of a header when it stopped: digits, a space, part of the checksum.
_PARTIAL_HEADER = re.compile(rb"([0-9]+( [0-9a-f]{0,8})?)?")


def _header(line: bytes) -> tuple[int, int] | None:
    """The body length a line announces and where its body starts, if its header is whole."""
    head, space, rest = line.partition(b" ")
    crc_text, space2, _body = rest.partition(b" ")
    if not (head.isdigit() and space and space2 and len(crc_text) == 8):
        return None
    try:
        int(crc_text, 16)
    except ValueError:
        return None
    return int(head), len(head) + len(crc_text) + 2


def cut_short(line: bytes) -> bool:
    """True when ``line`` (the file's last bytes, no newline) is the start of a record that an
    interrupted append left: its header is incomplete, or its body shorter than announced
    (zeros after it are space a crash allocated but never wrote). A whole record whose newline
    is missing or changed is damage, not a torn write."""
    line = line.rstrip(b"\0")
    header = _header(line)
    if header is None:
        return _PARTIAL_HEADER.fullmatch(line) is not None
    length, body_at = header
    body = line[body_at:]
    # A prefix of a record's JSON object never parses; a body that does is whole (its length
    # digits are what changed).
    return len(body) < length and not _parses(body)


def _parses(body: bytes) -> bool:
    try:
        json.loads(body)
    except ValueError:
        return False
    return True


def unframe(line: bytes) -> dict[str, Any] | None:
    """The record of one line (without its newline), or None if it is not intact."""
    head, _, rest = line.partition(b" ")
    crc_text, _, body = rest.partition(b" ")
    try:
        length, crc = int(head), int(crc_text, 16)
    except ValueError:
        return None
    if len(head) == 0 or len(body) != length or zlib.crc32(body) != crc:
        return None
    try:
        record = json.loads(body)
    except ValueError:
        return None
    return record if isinstance(record, dict) else None


@dataclass
class Damage:
    """Bytes ``start``..``end`` of the file are not intact records."""

    start: int
    end: int


@dataclass
class Scan:
    """Every intact record (with where it starts and ends), the damage (bytes that are not
    intact records, the last ones included unless they are a record cut short), and where a torn
    tail starts (``size`` when there is none)."""

    size: int
    records: list[tuple[int, int, dict[str, Any]]] = field(default_factory=list)
    damage: list[Damage] = field(default_factory=list)
    torn_at: int = 0
    unterminated: bool = False  # the last record is whole but lacks its newline

    @property
    def torn_bytes(self) -> int:
        return self.size - self.torn_at

    def describe_damage(self, name: str) -> str:
        first = self.damage[0]
        following = sum(1 for start, _end, _r in self.records if start >= first.end)
        lost = sum(d.end - d.start for d in self.damage)
        where = (f"{following} intact record(s) follow the first damage" if following else
                 "its last record is complete but does not match its checksum: an acknowledged "
                 "write, not one a crash cut short")
        return (f"{name} is damaged at byte {first.start} ({len(self.damage)} damaged region(s), "
                f"{lost} bytes), and {where}")


def scan(data: bytes) -> Scan:
    result = Scan(size=len(data))
    bad_from: int | None = None
    pos = 0
    while pos < len(data):
        end = data.find(b"\n", pos)
        if end < 0:  # no newline: the last bytes, torn only if they are a record cut short
            last = data[pos:]
            record = unframe(last)
            if bad_from is None and record is None and cut_short(last):
                result.torn_at = pos
                return result
            if record is not None and isinstance(record.get("revision"), int):
                # Whole but for its newline (the append stopped at its last byte): a record.
                if bad_from is not None:
                    result.damage.append(Damage(bad_from, pos))
                result.records.append((pos, len(data), record))
                result.unterminated = True
                result.torn_at = len(data)
                return result
            bad_from = pos if bad_from is None else bad_from
            break
        record = unframe(data[pos:end])
        if record is None or not isinstance(record.get("revision"), int):
            bad_from = pos if bad_from is None else bad_from
        else:
            if bad_from is not None:
                result.damage.append(Damage(bad_from, pos))
                bad_from = None
            result.records.append((pos, end + 1, record))
        pos = end + 1
    if bad_from is not None:
        result.damage.append(Damage(bad_from, len(data)))
    result.torn_at = len(data)
    return result


def read_snapshot(data: bytes) -> dict[str, Any]:
    """The state a snapshot file holds; ``ValueError`` saying what is wrong if it is not intact."""
    if not data.strip():
        raise ValueError("it is empty")
    if data.lstrip().startswith(b"{"):  # written before snapshots had a checksum
        state = json.loads(data)
    else:
        if not data.endswith(b"\n") or (state := unframe(data[:-1])) is None:
            raise ValueError("its checksum or length does not match its content")
    if not isinstance(state, dict) or not isinstance(state.get("revision"), int) \
            or not isinstance(state.get("models"), dict):
        raise ValueError("it does not hold a revision and models")
    return state


def missing_revisions(snapshot_revision: int, revisions: Iterable[int]) -> range | None:
    """The revisions that neither the snapshot nor the journal holds, if any: the journal's first
    record after the snapshot must be the revision right after it (a journal keeps every commit
    in order; records the snapshot already holds may precede it)."""
    following = next((r for r in revisions if r > snapshot_revision), None)
    if following is None or following == snapshot_revision + 1:
        return None
    return range(snapshot_revision + 1, following)


@dataclass(frozen=True)
class Break:
    """Where the journal's records stop following each other: the record at byte ``at``, of
    revision ``found`` (or, marked by a repair, accounting from it), follows revision ``after``."""

    at: int
    after: int
    found: int

    @property
    def missing(self) -> range:
        return range(self.after + 1, self.found)

    def describe(self) -> str:
        if self.found > self.after + 1:
            return (f"revisions {self.after + 1}..{self.found - 1} are missing between the records of "
                    f"revisions {self.after} and {self.found} (byte {self.at}: a record removed?)")
        return (f"the record at byte {self.at} (revision {self.found}) follows revision {self.after}: "
                f"repeated or out of order")


def first_revision(record: dict[str, Any]) -> int:
    """The first revision a record accounts for: its own, or for a repair's marker of lost
    revisions (``{"revision": last, "lost": first}``, no change) the first it marks."""
    revision: int = record["revision"]
    lost = record.get("lost")
    return lost if isinstance(lost, int) and not isinstance(lost, bool) and 0 < lost <= revision else revision


def breaks(snapshot_revision: int, records: Iterable[tuple[int, int, dict[str, Any]]]) -> list[Break]:
    """Every place where a journal record after the snapshot's revision does not take the next
    revision after the record before it. Every commit is one record and takes the next revision,
    so a missing record (not a torn tail: a whole line gone) shows here and nowhere else. The
    first record after the snapshot is ``missing_revisions``' to judge."""
    found: list[Break] = []
    previous: int | None = None
    for start, _end, record in records:
        revision = record["revision"]
        if revision <= snapshot_revision and previous is None:
            continue  # the snapshot already holds it
        if previous is not None and first_revision(record) != previous + 1:
            found.append(Break(start, previous, first_revision(record)))
        if previous is None or revision > previous:
            previous = revision
    return found


def describe_missing(missing: range, snapshot: str) -> str:
    return (f"the journal does not continue {snapshot}: its next record is revision {missing.stop}, "
            f"so revisions {missing.start}..{missing.stop - 1} are in neither (a snapshot deleted, "
            f"or replaced by an older one?)")


# --- N-Triples terms ---------------------------------------------------------------------------


def nt(triple: Triple) -> str:
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


def parse_nt(statement: str, bnodes: dict[str, BNode]) -> Triple:
    if '"' not in statement:
        # Names and blank nodes only, as `nt` writes most statements: no tokenizer, and each
        # name parsed once (a recovery reads the same names over and over).
        parts = statement.split()
        if len(parts) == 3 and all(_plain(part) for part in parts):
            s, p, o = (_plain_node(part, bnodes) for part in parts)
            return (s, p, o)
    tokens = tokenize(statement)
    if len(tokens) != 3:
        raise KbError(f"corrupt journal statement {statement!r}")
    return (_node(tokens[0], bnodes), _node(tokens[1], bnodes), _node(tokens[2], bnodes))


def _plain(part: str) -> bool:
    """A token the tokenizer reads as this very text: ``<iri>`` without other brackets, ``_:x``."""
    if part.startswith("<"):
        return part.endswith(">") and part.count("<") == 1 and part.count(">") == 1
    return part.startswith("_:")


def _plain_node(part: str, bnodes: dict[str, BNode]) -> Node:
    if part.startswith("_:"):
        label = part[2:]
        return bnodes.setdefault(label, BNode(label))
    return _name(part)


@lru_cache(maxsize=32768)
def _name(text: str) -> URIRef:
    return parse_name(text, "journal")


def _node(token: Token, bnodes: dict[str, BNode]) -> Node:
    if token.literal:
        lit: Literal = parse_literal(token.text)
        return lit
    if token.text.startswith("_:"):
        label = token.text[2:]
        return bnodes.setdefault(label, BNode(label))
    return parse_name(token.text, "journal")
