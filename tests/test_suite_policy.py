"""The default suite asserts behaviour, never speed: nothing in it may fail because the machine is
busy. Speed is measured by `situated bench`."""

from __future__ import annotations

import hypothesis


def test_property_tests_have_no_time_limit_per_example() -> None:
    # Hypothesis fails an example that takes over 200 ms by default: a speed assertion that a busy
    # machine breaks. The suite's profile removes it for every property test, present and future.
    assert hypothesis.settings.default.deadline is None
