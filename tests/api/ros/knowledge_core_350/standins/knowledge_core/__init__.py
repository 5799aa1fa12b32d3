"""Stand-in for the ``knowledge_core`` package: its ``api`` is situated's client of the same ROS API."""
