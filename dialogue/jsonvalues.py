"""JSON values that come from outside (an ask role's configuration, an intent's `data`), held to
bounds every later reader of them can take.

A value decoded from a request is walked before anything else reads it, and what no reader needs is
refused with the place named: nesting deeper than `MAX_DEPTH` (a recursive reader — pydantic, a
serialiser, a ROS consumer's parser — runs out of stack or answers with a path thousands of steps
long), a number of more than `MAX_DIGITS` digits (Python's int() and str() refuse 4,300 and more,
as an error no caller expects; C++ readers take 64 bits), one that is not finite (``NaN`` and
``Infinity`` are no JSON: the serialised value would not parse again), and a lone surrogate in any
string or key (a Python string, but no UTF-8 document, so every later answer naming it would fail).

>>> check({"a": [1, 2.5, "x", {"b": None}]}, "data.other_data")
>>> check(float("nan"), "data.other_data")
Traceback (most recent call last):
    ...
dialogue.jsonvalues.JsonValueError: data.other_data: nan is not a finite number
"""

from __future__ import annotations

import math

from dialogue.errors import DialogueError
from kb.errors import InvalidUnicode
from kb.unicode import check_text

#: Digits of a number (a bound such as 10**30 has 31).
MAX_DIGITS = 100
#: Levels of objects and lists.
MAX_DEPTH = 32
#: An integer of more bits than this has more than MAX_DIGITS digits (10**100 has 333 bits);
#: below it, its digits are counted exactly, without converting a huge one to text.
_FEW_BITS = 400


class JsonValueError(DialogueError, ValueError):
    """A JSON value past the bounds; the message says what and where."""


def check(value: object, where: str) -> None:
    """Refuse (JsonValueError) a decoded JSON value past the bounds; `where` names it in the message.
    Iterative: a value as deep as a decoder allowed would exhaust the stack of a recursive walk."""
    pending: list[tuple[object, int]] = [(value, 1)]
    while pending:
        item, depth = pending.pop()
        if isinstance(item, str):
            _text(item, where)
        elif isinstance(item, bool) or item is None:
            continue
        elif isinstance(item, int):
            _integer(item, where)
        elif isinstance(item, float):
            if not math.isfinite(item):
                raise JsonValueError(f"{where}: {item} is not a finite number")
        elif isinstance(item, dict | list):
            if depth > MAX_DEPTH:
                raise JsonValueError(f"{where} is nested more than {MAX_DEPTH} levels deep")
            if isinstance(item, dict):
                for key in item:
                    _text(key, where)
            children = item.values() if isinstance(item, dict) else item
            pending.extend((child, depth + 1) for child in children)


def _integer(value: int, where: str) -> None:
    digits = len(str(abs(value))) if value.bit_length() <= _FEW_BITS else None
    if digits is None or digits > MAX_DIGITS:
        said = f"{digits} digits" if digits is not None else f"more than {MAX_DIGITS} digits"
        raise JsonValueError(f"{where} has a number of {said}; at most {MAX_DIGITS}")


def _text(text: object, where: str) -> None:
    if not isinstance(text, str):
        return  # a key of a dict built in Python; the model's own validation refuses it
    try:
        check_text(text, f"text of {where}")
    except InvalidUnicode as exc:
        raise JsonValueError(str(exc)) from None
