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

import gc
import sys
import threading
from collections.abc import Callable
from pathlib import Path
from types import FrameType
from typing import Any

import pyparsing
import rdflib
from rdflib.plugins.sparql.parser import parseQuery, parseUpdate

from kb.deadline import Deadline
from kb.errors import QueryTimeout

# Calls between two looks at the clock while parsing (pyparsing makes thousands per character).
_CHECK_EVERY = 256

Parser = Callable[[str], Any]

#: Where the parser's own code is: pyparsing's grammar engine and rdflib's.
_PARSER_FILES = tuple(str(Path(module.__file__ or "").parent) for module in (pyparsing, rdflib))


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

    def trace(frame: FrameType, event: str, arg: Any) -> None:
        nonlocal calls
        calls += 1
        if not calls % _CHECK_EVERY and not deadline.remaining() and _in_the_parse(frame):
            raise QueryTimeout(deadline.seconds)  # ends the parse (and the tracing)

    previous = sys.gettrace()
    sys.settrace(trace)  # this thread only; 'call' events only (no local trace function)
    try:
        tree = parser(text)
    finally:
        sys.settrace(previous)
    deadline.check()  # a parse that swallowed the error still counts
    return tree


def _in_the_parse(frame: FrameType) -> bool:
    """Whether a call is the parser's own, where an error stops the parse. Python also runs code
    in the middle of a parse that is not the parse's: finalizers, weak reference and garbage
    collector callbacks (a profiler's, a test plugin's), in whatever frame allocated. What they
    raise is printed and dropped, and a trace function that raised is removed: stopped there, the
    parse would run on to its end unwatched."""
    if not frame.f_code.co_filename.startswith(_PARSER_FILES):
        return False
    callbacks = {code for callback in gc.callbacks if (code := getattr(callback, "__code__", None))}
    caller: FrameType | None = frame
    while callbacks and caller is not None:
        if caller.f_code in callbacks:
            return False
        caller = caller.f_back
    return True
