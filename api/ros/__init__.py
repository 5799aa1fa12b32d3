"""situated on a ROS 2 graph: knowledge_core's and the chatbot's interfaces, served by the same
process, KB and dialogue engine as the HTTP service (`situated ros run`).

Nothing here imports rclpy until a node is started: the rest of the service never needs ROS.
"""
