"""The ask role's configuration as JSON: decoded within the bounds a form's schema ever needs
(dialogue.jsonvalues; a field's schema is three levels: configuration, properties, field).

A configuration comes from the request (an opaque string of chatbot_msgs' DialogueRole), so its
JSON is decoded before anything else reads it, and what no field schema needs is refused with the
place named: a number of more than `MAX_DIGITS` digits (Python's int() refuses 4,300 and more, as
an error no caller expects), one that is not finite (``1e999``, ``NaN``), nesting deeper than
`MAX_DEPTH` (the decoder recurses: 10,000 levels exhaust its stack), and a lone surrogate in any
string or key (JSON's ``"\\ud800"`` decodes to one: a Python string, but no UTF-8 document, so every
later answer naming it — the turn's results, its trace — would fail).

>>> decode('{"a": [1, 2.5, "x"]}')
{'a': [1, 2.5, 'x']}
"""

from __future__ import annotations

import json
import math
from typing import Any

from dialogue.errors import DialogueError
from dialogue.jsonvalues import MAX_DEPTH, MAX_DIGITS, JsonValueError, check

__all__ = ["MAX_DEPTH", "MAX_DIGITS", "ConfigurationError", "decode"]
_WHERE = "the ask role's configuration"


class ConfigurationError(DialogueError, ValueError):
    """JSON the configuration may not hold; the message says what and where."""


def _integer(text: str) -> int:
    digits = len(text.lstrip("-"))
    if digits > MAX_DIGITS:
        raise ConfigurationError(f"{_WHERE} has a number of {digits} digits; at most {MAX_DIGITS}")
    return int(text)


def _real(text: str) -> float:
    if len(text) > MAX_DIGITS:
        raise ConfigurationError(f"{_WHERE} has a number of {len(text)} characters; at most {MAX_DIGITS}")
    value = float(text)
    if not math.isfinite(value):
        raise ConfigurationError(f"{_WHERE}: {text} is not a finite number")
    return value


def _constant(text: str) -> float:
    raise ConfigurationError(f"{_WHERE}: {text} is not a finite number")


def decode(text: str) -> Any:
    """The JSON value of `text`; ConfigurationError for what the bounds refuse, ValueError
    (json.JSONDecodeError) for text that is no JSON."""
    try:
        value = json.loads(text, parse_int=_integer, parse_float=_real, parse_constant=_constant)
    except RecursionError:
        raise ConfigurationError(f"{_WHERE} is nested more than {MAX_DEPTH} levels deep") from None
    _check(value)
    return value


def _check(value: Any) -> None:
    try:
        check(value, _WHERE)
    except JsonValueError as exc:
        raise ConfigurationError(str(exc)) from None
