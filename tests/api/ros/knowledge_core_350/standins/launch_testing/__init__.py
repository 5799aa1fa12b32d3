"""Stand-in for ``launch_testing`` (not on PyPI). Tests marked ``post_shutdown_test`` check the
launched process's exit code after it stopped: there is no launched process here, so they are
skipped with that reason, and the fixture checks how situated's node stops instead."""

from __future__ import annotations

import unittest
from collections.abc import Callable
from typing import TypeVar

from launch_testing import actions as actions
from launch_testing import asserts as asserts

T = TypeVar("T")
POST_SHUTDOWN = "post-shutdown test of the launched process: the fixture checks how situated's node stops"


def post_shutdown_test() -> Callable[[T], T]:
    return unittest.skip(POST_SHUTDOWN)  # type: ignore[return-value]
