"""Stand-in for ROS 2's ``launch`` (not on PyPI): the launch description knowledge_core's tests build
is inert, since situated's node is started by the test fixture (tests/api/ros/test_knowledge_core_compat.py)."""

from __future__ import annotations

from typing import Any


class LaunchDescription:
    def __init__(self, actions: list[Any] | None = None) -> None:
        self.actions = list(actions or [])

    def add_action(self, action: Any) -> None:
        self.actions.append(action)
