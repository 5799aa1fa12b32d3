"""JSON values from outside are held to bounds every later reader can take."""

from __future__ import annotations

import json

import pytest

from dialogue.jsonvalues import MAX_DEPTH, JsonValueError, check


def nested(levels: int) -> object:
    return json.loads("[" * levels + "]" * levels)


def test_what_any_reader_takes_passes() -> None:
    check({"a": [1, -2.5e10, "é", True, None, {"b": [10 ** 99]}]}, "v")
    check(nested(MAX_DEPTH), "v")


@pytest.mark.parametrize(("value", "says"), [
    (nested(MAX_DEPTH + 1), "v is nested more than 32 levels deep"),
    ({"a": nested(MAX_DEPTH)}, "v is nested more than 32 levels deep"),
    (float("nan"), "v: nan is not a finite number"),
    ([float("inf")], "v: inf is not a finite number"),
    (-(10 ** 100), "v has a number of 101 digits; at most 100"),
    pytest.param(10 ** 10_000, "v has a number of more than 100 digits", id="10**10000"),
    ({"\ud800": 1}, "text of v is not valid Unicode: it holds the lone surrogate U+D800"),
    (["ok", ["\udc00"]], "lone surrogate U+DC00"),
])
def test_what_a_reader_cannot_take_is_refused_saying_what_and_where(value: object, says: str) -> None:
    with pytest.raises(JsonValueError) as refused:
        check(value, "v")
    assert says in str(refused.value)


def test_a_value_deeper_than_the_stack_is_walked_without_recursion() -> None:
    deep: object = 1
    for _ in range(200_000):
        deep = [deep]
    with pytest.raises(JsonValueError, match="nested more than 32 levels"):
        check(deep, "v")
