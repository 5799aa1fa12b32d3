"""The ask role's configuration JSON, decoded within bounds: what no field schema needs is refused."""

from __future__ import annotations

import json

import pytest

from dialogue.ask.jsontext import MAX_DEPTH, ConfigurationError, decode


def nested(levels: int) -> str:
    return "[" * levels + "]" * levels


@pytest.mark.parametrize(("text", "message"), [
    ("9" * 5000, "5000 digits"),  # past int()'s 4,300 digits: a ValueError no caller expected
    ("-" + "1" * 101, "101 digits"),
    ("1" * 60 + "." + "1" * 60, "121 characters"),
    ("1e999", "not a finite number"), ("-1e999", "not a finite number"),
    ("NaN", "not a finite number"), ("Infinity", "not a finite number"),
    (nested(10_000), "nested more than 32 levels"),  # the decoder's own RecursionError
    (nested(MAX_DEPTH + 1), "nested more than 32 levels"),
    ('{"a": ' * 33 + "1" + "}" * 33, "nested more than 32 levels"),
    ('"How old\\ud800?"', "lone surrogate U\\+D800 at character 7"),
    ('{"a\\udc00ge": 1}', "lone surrogate U\\+DC00"),
    ('{"enum": ["x", ["\\udfff"]]}', "lone surrogate U\\+DFFF"),
])
def test_what_no_schema_needs_is_refused_saying_what(text: str, message: str) -> None:
    with pytest.raises(ConfigurationError, match=message):
        decode(text)


def test_what_a_schema_may_hold_is_decoded_as_json() -> None:
    value = {"question": "\U0001f600?", "result_schema_properties": {"a": {"maximum": 10**30, "minimum": -1.5e10}}}
    text = json.dumps(value)  # ASCII: the emoji as a surrogate pair, which is valid
    assert decode(text) == value
    assert decode(nested(MAX_DEPTH)) == json.loads(nested(MAX_DEPTH))


def test_text_that_is_no_json_is_the_decoders_error() -> None:
    with pytest.raises(json.JSONDecodeError):
        decode("{oops")
