"""What still reads of a damaged snapshot: every statement, before the damage and after it.

A snapshot is one JSON document, ``{"revision": N, "models": {name: {"add": [...], "remove":
[...]}}, "expiries": [[model, statement, at], ...]}``. A JSON parser stops at the first damaged
byte, so 512 zero bytes a third of the way in used to leave two thirds of the statements behind,
though they still read. Here the document is read token by token: where a byte starts no JSON
token, the reader skips to the next place a string starts after ``,``, ``[`` or ``{`` (in JSON
text a raw quote there is always structure, never inside a string, and no statement ends with a
comma) and goes on in the containers that were open. Each statement is kept if it parses.

What cannot be seen: a model or list boundary inside the damaged bytes. The statements read after
the damage, until their list closes, are kept in the list open where the damage began (the
repair says how many); a flipped bit that leaves a statement parsable reads as that statement
(the snapshot's checksum only says that something changed).
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from typing import Any

from rdflib import BNode

from kb.errors import KbError
from kb.records import parse_nt

# A JSON token (strings without raw control characters, which JSON text never holds), or space.
_TOKEN = re.compile(rb'"(?:[^"\\\x00-\x1f]|\\.)*"|-?[0-9]+(?:\.[0-9]+)?(?:[eE][+-]?[0-9]+)?'
                    rb"|[{}\[\]:,]|true|false|null|[ \t\r\n]+")
# Where reading can resume after damage: the quote that opens a string after , [ or {.
_RESUME = re.compile(rb'[,\[{]"')


@dataclass
class Salvaged:
    """The state rebuilt from what still reads, and what was kept and dropped."""

    state: dict[str, Any]
    kept: int = 0
    dropped: int = 0
    after_damage: int = 0  # kept statements read after damaged bytes, in the list open there
    damaged: bool = False


@dataclass
class _Frame:
    kind: str  # "{" or "["
    key: str | None  # the key this container is the value of (None in a list)
    pending: str | None = None  # an object's key read, its value not yet
    items: list[Any] = field(default_factory=list)


class _Reader:
    def __init__(self) -> None:
        self.result = Salvaged({"revision": 0, "models": {}, "expiries": []})
        self.stack: list[_Frame] = []
        self.bnodes: dict[str, BNode] = {}
        self.damaged_list: _Frame | None = None  # the list open where damage began

    def path(self) -> list[str | None]:
        return [f.key for f in self.stack]

    def open(self, kind: str) -> None:
        top = self.stack[-1] if self.stack else None
        key = top.pending if top is not None and top.kind == "{" else None
        if top is not None and top.kind == "{":
            top.pending = None
        self.stack.append(_Frame(kind, key))

    def close(self) -> None:
        if not self.stack:
            return
        frame = self.stack.pop()
        if frame is self.damaged_list:
            self.damaged_list = None
        path = self.path()
        if frame.kind == "[" and path == [None, "expiries"]:  # one [model, statement, at]
            self._expiry(frame.items)

    def value(self, token: bytes) -> None:
        try:
            decoded = json.loads(token)
        except ValueError:
            return
        top = self.stack[-1] if self.stack else None
        if top is None:
            return
        if top.kind == "{":
            if top.pending is None and isinstance(decoded, str):
                top.pending = decoded  # a key (its ':' follows)
                return
            if top.pending == "revision" and len(self.stack) == 1 and isinstance(decoded, int):
                self.result.state["revision"] = decoded
            top.pending = None
            return
        path = self.path()
        if len(path) == 4 and path[1] == "models" and path[3] in ("add", "remove"):
            self._statement(str(path[2]), str(path[3]), decoded)
        elif path[1:] == ["expiries", None]:
            top.items.append(decoded)

    def _statement(self, model: str, key: str, statement: Any) -> None:
        change = self.result.state["models"].setdefault(model, {"add": [], "remove": []})
        if self._reads(statement):
            change[key].append(statement)
            self.result.kept += 1
            if self.damaged_list is not None and self.damaged_list is self.stack[-1]:
                self.result.after_damage += 1
        else:
            self.result.dropped += 1

    def _expiry(self, entry: list[Any]) -> None:
        if len(entry) == 3 and isinstance(entry[0], str) and self._reads(entry[1]) \
                and isinstance(entry[2], int | float) and not isinstance(entry[2], bool):
            self.result.state["expiries"].append(entry)
        else:
            self.result.dropped += 1

    def _reads(self, statement: Any) -> bool:
        if not isinstance(statement, str):
            return False
        try:
            parse_nt(statement, self.bnodes)
        except KbError:
            return False
        return True

    def damage(self) -> None:
        self.result.damaged = True
        if self.damaged_list is None and self.stack and self.stack[-1].kind == "[":
            self.damaged_list = self.stack[-1]


def salvage(data: bytes) -> Salvaged | None:
    """Every statement of a snapshot that still reads; None when not even its models start."""
    start = data.find(b'{"')
    if start < 0:
        return None
    text, reader, pos = data[start:], _Reader(), 0
    while pos < len(text):
        match = _TOKEN.match(text, pos)
        if match is None:
            reader.damage()
            resume = _RESUME.search(text, pos + 1)
            if resume is None:
                break
            pos = resume.start() + 1
            continue
        token, pos = match.group(), match.end()
        if token in (b"{", b"["):
            reader.open(token.decode())
        elif token in (b"}", b"]"):
            reader.close()
        elif token[:1] not in (b",", b":", b" ", b"\t", b"\r", b"\n"):
            reader.value(token)
    if not reader.result.state["models"] and not reader.result.kept and b'"models"' not in text:
        return None
    return reader.result
