"""The data directory's formats: checksummed records, the scan that tells a torn tail from
corruption, and N-Triples terms (blank nodes included, unlike the KB's statement syntax).

A record is one line, ``<length> <crc32> <json>\\n`` (compact JSON never holds a raw newline).
The journal is a sequence of records; the snapshot is one record (older snapshots were bare
JSON, still read). A scan reads every line: a bad line followed by an intact record is
corruption (acknowledged writes come after it); bad bytes after the last intact record are a
torn tail, what a crash in the middle of an append leaves.
"""

from __future__ import annotations

import json
import zlib
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

from rdflib import BNode, Literal, URIRef

from kb.errors import KbError
from kb.terms import Node, Token, Triple, parse_literal, parse_name, tokenize


def frame(payload: dict[str, Any]) -> bytes:
    body = json.dumps(payload, separators=(",", ":")).encode()
    return b"%d %08x " % (len(body), zlib.crc32(body)) + body + b"\n"


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
    """Every intact record (with where it starts and ends), damage followed by intact records,
    and where a torn tail starts (``size`` when there is none)."""

    size: int
    records: list[tuple[int, int, dict[str, Any]]] = field(default_factory=list)
    damage: list[Damage] = field(default_factory=list)
    torn_at: int = 0

    @property
    def torn_bytes(self) -> int:
        return self.size - self.torn_at

    def describe_damage(self, name: str) -> str:
        first = self.damage[0]
        following = sum(1 for start, _end, _r in self.records if start >= first.end)
        lost = sum(d.end - d.start for d in self.damage)
        return (f"{name} is damaged at byte {first.start} ({len(self.damage)} damaged region(s), "
                f"{lost} bytes), and {following} intact record(s) follow the first damage")


def scan(data: bytes) -> Scan:
    result = Scan(size=len(data))
    bad_from: int | None = None
    pos = 0
    while pos < len(data):
        end = data.find(b"\n", pos)
        if end < 0:  # no newline: an incomplete last line
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
    result.torn_at = bad_from if bad_from is not None else len(data)
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
