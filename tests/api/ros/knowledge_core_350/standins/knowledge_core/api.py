"""``knowledge_core.api``: situated's ROS client (``api.ros.client.kb``), which is knowledge_core's."""

from api.ros.client.kb import KB, KbError

__all__ = ["KB", "KbError"]
