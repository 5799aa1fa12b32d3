"""Stand-in for ``launch_ros`` (not on PyPI): see ``launch``."""

from launch_ros import actions as actions
