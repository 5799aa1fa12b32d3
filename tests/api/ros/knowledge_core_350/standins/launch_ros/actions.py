"""``launch_ros.actions.Node``: what would be launched, recorded and never started."""

from __future__ import annotations

from typing import Any


class Node:
    def __init__(self, **description: Any) -> None:
        self.description = description
