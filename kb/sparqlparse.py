"""rdflib's SPARQL parser, safe to call from any thread and held to a query's deadline.

rdflib parses SPARQL with a pyparsing grammar, one per process. pyparsing learns how many
arguments each parse action takes on its first calls, without a lock: a fresh process that parses
from several threads at once can learn a wrong count and keep it, and from then on every parse
fails (issue 26: /sparql answered 500 until restart). So parses take turns (pyparsing is pure
Python: under the GIL they never ran in parallel anyway), and the first one, which also prepares
the whole grammar (pyparsing's ``streamline``), runs on its own and is never interrupted.

A parse costs far more than its length suggests (a 4 KB sum of numbers takes seconds), so it
counts against the query's deadline: waiting for its turn, then parsing under a trace function
that looks at the clock every few hundred calls and stops the parse past the deadline
(``QueryTimeout``). The caller bounds the text first (kb.sparql): a parse also holds what it
builds in memory.
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Callable
from types import FrameType
from typing import Any

from rdflib.plugins.sparql.parser import parseQuery, parseUpdate

from kb.deadline import Deadline
from kb.errors import QueryTimeout

# Calls between two looks at the clock while parsing (pyparsing makes thousands per character).
_CHECK_EVERY = 256

Parser = Callable[[str], Any]


class _Grammar:
    """Turns at rdflib's grammar: it is one per process, so is what guards it."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._ready = False

    def parse(self, text: str, parser: Parser, deadline: Deadline | None) -> Any:
        if deadline is None:
            self._lock.acquire()
        elif not self._lock.acquire(timeout=deadline.remaining()):
            raise QueryTimeout(deadline.seconds, waiting=True)
        try:
            if not self._ready:
                # Both grammars prepared by a parse nobody interrupts (an interrupted streamline
                # would leave the grammar half changed for every later parse).
                parseQuery("ASK {}")
                parseUpdate("INSERT DATA {}")
                self._ready = True
            return parser(text) if deadline is None else _within(deadline, parser, text)
        finally:
            self._lock.release()


_GRAMMAR = _Grammar()


def parse(text: str, parser: Parser, deadline: Deadline | None = None) -> Any:
    """``parser(text)`` (rdflib's ``parseQuery`` or ``parseUpdate``) in its turn, within the
    deadline."""
    return _GRAMMAR.parse(text, parser, deadline)


def _within(deadline: Deadline, parser: Parser, text: str) -> Any:
    calls = 0
    check = deadline.check

    def trace(frame: FrameType, event: str, arg: Any) -> None:
        nonlocal calls
        calls += 1
        if not calls % _CHECK_EVERY:
            check()  # QueryTimeout ends the parse (and the tracing)

    previous = sys.gettrace()
    sys.settrace(trace)  # this thread only; 'call' events only (no local trace function)
    try:
        tree = parser(text)
    finally:
        sys.settrace(previous)
    check()  # a parse that swallowed the error still counts
    return tree
