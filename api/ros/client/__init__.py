"""A Python client of knowledge_core's ROS API (``/kb/*``), for situated's node or knowledge_core's:
``api.ros.client.kb.KB`` is knowledge_core 3.5's ``knowledge_core.api.KB``, written from its
documented behaviour. ``kb`` imports rclpy and kb_msgs (run it in a ROS 2 environment); ``patterns``
does not.
"""
