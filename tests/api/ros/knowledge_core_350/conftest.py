"""knowledge_core 3.5's own ROS tests, vendored unchanged (Apache-2.0, LICENSE beside them). They
import rclpy and run under ROS 2 in a subprocess (tests/api/ros/test_knowledge_core_compat.py), with
the stand-ins of ``standins/`` on their path: never collected by the project's own test run."""

collect_ignore_glob = ["test_*_350.py", "standins/*"]
