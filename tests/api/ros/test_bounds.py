"""A ROS request's counts and text are bounded as a REST request's are."""

from __future__ import annotations

import pytest

from api.errors import ApiError
from api.ros.bounds import RequestBounds
from api.settings import Limits

LIMITS = Limits(max_patterns=2, max_statements=3, max_models=1, max_body_bytes=2048)


@pytest.mark.parametrize(
    ("request_", "code"),
    [
        ({"patterns": ["?a b c"] * 3}, "too_many_patterns"),
        ({"statements": ["a b c"] * 4}, "too_many_statements"),
        ({"models": ["m1", "m2"]}, "too_many_models"),
        ({"statements": ["a b " + "c" * 2045]}, "request_too_large"),
        ({"statements": ["a b " + "c" * 1000], "texts": ["x" * 1045]}, "request_too_large"),
    ],
)
def test_past_a_limit_is_a_413_that_names_it(request_: dict[str, list[str]], code: str) -> None:
    with pytest.raises(ApiError) as refused:
        RequestBounds(LIMITS).check(**request_)
    assert refused.value.status == 413 and refused.value.code == code
    assert "limit" in refused.value.message


def test_within_the_limits_passes() -> None:
    RequestBounds(LIMITS).check(patterns=["?a b c"] * 2, statements=["a b " + "c" * 2000], models=["m"])
