"""The ROS 2 nodes: every module here imports rclpy and the generated interfaces, so nothing
imports this package until `situated ros run` has checked they are there (`api.ros.cli`). Their
behaviour is tested on a real graph (tests/api/ros), not by importing them in the test process."""
