"""A plain rclpy client in its own process, driven by the tests over JSON lines (stdin -> stdout).

The test process never imports rclpy (it runs in the project's venv, not in ROS's environment):
it starts this script with the ROS environment, sends one command per line and reads one answer
per line. Messages travel as JSON objects of their fields (nested messages as objects, arrays as
lists). Commands (``op``):

- ``call``: ``service``, ``type`` ("kb_msgs/srv/Query"), ``request`` -> ``{"response": {...}}``
- ``publish``: ``topic``, ``type``, ``message`` (``latched``: transient local), once someone subscribes;
  ``unpublish``: ``topic`` (the publisher destroyed); ``subscribers``: ``topic`` -> ``{"count"}``;
  ``publisher_count``: ``topic`` -> ``{"count", "matched"}`` (those this probe's subscription is matched with)
- ``subscribe``: ``topic``, ``type`` -> later ``messages``: ``topic``, ``count``, ``timeout``;
  ``unsubscribe``: ``topic`` (its messages stay readable)
- ``goal``: ``action``, ``type``, ``goal``, ``uuid`` (hex, optional) -> ``{"accepted", "goal"}``;
  ``result``: ``goal`` -> ``{"status", "result", "feedback"}``; ``status``: ``goal``; ``cancel``: ``goal``
- ``env``: the ROS environment variables this process runs with; ``quit``.

Every answer has ``ok``; a failure answers ``{"ok": false, "error": "..."}``.
"""

from __future__ import annotations

import importlib
import json
import os
import sys
import threading
import time
import uuid
from typing import Any

import rclpy
from action_msgs.msg import GoalStatus
from rclpy.action import ActionClient
from rclpy.executors import MultiThreadedExecutor
from rclpy.node import Node
from rclpy.qos import QoSDurabilityPolicy, QoSProfile, QoSReliabilityPolicy
from unique_identifier_msgs.msg import UUID


def message_type(name: str) -> Any:
    package, kind, cls = name.split("/")
    return getattr(importlib.import_module(f"{package}.{kind}"), cls)


def to_dict(message: Any) -> Any:
    if hasattr(message, "get_fields_and_field_types"):
        return {field: to_dict(getattr(message, field)) for field in message.get_fields_and_field_types()}
    if isinstance(message, (list, tuple)) or type(message).__name__ == "ndarray" or hasattr(message, "tolist"):
        return [to_dict(item) for item in (message.tolist() if hasattr(message, "tolist") else message)]
    if isinstance(message, bytes):
        return list(message)
    return message


def fill(message: Any, values: dict[str, Any]) -> Any:
    for field, value in values.items():
        current = getattr(message, field)
        if isinstance(value, dict):
            fill(current, value)
        elif isinstance(value, list) and value and isinstance(value[0], dict):
            item_type = message.SLOT_TYPES[list(message.get_fields_and_field_types()).index(field)]
            cls = message_type(f"{item_type.value_type.namespaces[0]}/{item_type.value_type.namespaces[1]}/"
                               f"{item_type.value_type.name}")
            setattr(message, field, [fill(cls(), item) for item in value])
        else:
            setattr(message, field, value)
    return message


def wait(future: Any, timeout: float) -> Any:
    end = time.monotonic() + timeout
    while not future.done():
        if time.monotonic() > end:
            raise TimeoutError(f"no answer in {timeout} s")
        time.sleep(0.002)
    return future.result()


class Probe:
    def __init__(self) -> None:
        self.node = Node("situated_test_probe")
        self.executor = MultiThreadedExecutor(num_threads=2)
        self.executor.add_node(self.node)
        self.thread = threading.Thread(target=self.executor.spin, daemon=True)
        self.thread.start()
        self.clients: dict[str, Any] = {}
        self.received: dict[str, list[Any]] = {}
        self.subscriptions: dict[str, Any] = {}
        self.publishers: dict[str, Any] = {}
        self.goals: dict[str, Any] = {}
        self.feedback: dict[str, list[Any]] = {}
        self.results: dict[str, Any] = {}
        self.lock = threading.Lock()

    def call(self, service: str, type: str, request: dict[str, Any], timeout: float = 30.0) -> dict[str, Any]:
        kind = message_type(type)
        key = f"{type} {service}"
        if key not in self.clients:
            self.clients[key] = self.node.create_client(kind, service)
        client = self.clients[key]
        if not client.wait_for_service(timeout_sec=timeout):
            raise TimeoutError(f"service {service} not available in {timeout} s")
        response = wait(client.call_async(fill(kind.Request(), request)), timeout)
        return {"response": to_dict(response)}

    def subscribe(self, topic: str, type: str, latched: bool = False) -> dict[str, Any]:
        if topic not in self.subscriptions:
            self.received[topic] = []

            def keep(message: Any) -> None:
                with self.lock:
                    self.received[topic].append(to_dict(message))

            qos = QoSProfile(depth=100, reliability=QoSReliabilityPolicy.RELIABLE,
                             durability=QoSDurabilityPolicy.TRANSIENT_LOCAL if latched
                             else QoSDurabilityPolicy.VOLATILE)
            self.subscriptions[topic] = self.node.create_subscription(message_type(type), topic, keep, qos)
        return {}

    def unsubscribe(self, topic: str) -> dict[str, Any]:
        self.node.destroy_subscription(self.subscriptions.pop(topic))
        return {}

    def messages(self, topic: str, count: int = 1, timeout: float = 30.0) -> dict[str, Any]:
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            with self.lock:
                if len(self.received[topic]) >= count:
                    break
            time.sleep(0.01)
        with self.lock:
            return {"messages": list(self.received[topic])}

    def publish(self, topic: str, type: str, message: dict[str, Any], subscribers: int = 1,
                timeout: float = 30.0, latched: bool = False) -> dict[str, Any]:
        if topic not in self.publishers:
            qos = QoSProfile(depth=10, reliability=QoSReliabilityPolicy.RELIABLE,
                             durability=QoSDurabilityPolicy.TRANSIENT_LOCAL if latched
                             else QoSDurabilityPolicy.VOLATILE)
            self.publishers[topic] = self.node.create_publisher(message_type(type), topic, qos)
        publisher = self.publishers[topic]
        end = time.monotonic() + timeout
        while publisher.get_subscription_count() < subscribers:  # discovery takes a moment
            if time.monotonic() > end:
                raise TimeoutError(f"nobody subscribes to {topic}")
            time.sleep(0.01)
        publisher.publish(fill(message_type(type)(), message))
        return {}

    def unpublish(self, topic: str) -> dict[str, Any]:
        """Stop publishing ``topic`` (as a perception node does when a person goes)."""
        self.node.destroy_publisher(self.publishers.pop(topic))
        return {}

    def subscribers(self, topic: str) -> dict[str, Any]:
        return {"count": self.node.count_subscribers(topic)}

    def publisher_count(self, topic: str) -> dict[str, Any]:
        """Publishers of ``topic`` on the graph, and those matched with this probe's subscription."""
        subscription = self.subscriptions.get(topic)
        return {"count": self.node.count_publishers(topic),
                "matched": subscription.get_publisher_count() if subscription is not None else 0}

    def goal(self, action: str, type: str, goal: dict[str, Any], uuid_hex: str | None = None,
             timeout: float = 30.0) -> dict[str, Any]:
        kind = message_type(type)
        key = f"{type} {action}"
        if key not in self.clients:
            self.clients[key] = ActionClient(self.node, kind, action)
        client = self.clients[key]
        if not client.wait_for_server(timeout_sec=timeout):
            raise TimeoutError(f"action {action} not available in {timeout} s")
        goal_uuid = uuid.UUID(uuid_hex) if uuid_hex else uuid.uuid4()
        feedback: list[Any] = []
        self.feedback[goal_uuid.hex] = feedback

        def keep(message: Any) -> None:
            with self.lock:
                feedback.append(to_dict(message.feedback))

        handle = wait(client.send_goal_async(fill(kind.Goal(), goal), feedback_callback=keep,
                                             goal_uuid=UUID(uuid=list(goal_uuid.bytes))), timeout)
        self.goals[goal_uuid.hex] = handle
        if handle.accepted:  # asked for at once, as action clients do: a result comes even as the server stops
            self.results[goal_uuid.hex] = handle.get_result_async()
        return {"accepted": bool(handle.accepted), "goal": goal_uuid.hex}

    def result(self, goal: str, timeout: float = 30.0) -> dict[str, Any]:
        outcome = wait(self.results[goal], timeout)
        with self.lock:
            feedback = list(self.feedback[goal])
        return {"status": STATUS.get(outcome.status, str(outcome.status)), "result": to_dict(outcome.result),
                "feedback": feedback}

    def status(self, goal: str) -> dict[str, Any]:
        """The goal's status as its client last heard it (accepted, executing, succeeded...)."""
        return {"status": STATUS.get(self.goals[goal].status, str(self.goals[goal].status))}

    def cancel(self, goal: str, timeout: float = 30.0) -> dict[str, Any]:
        answer = wait(self.goals[goal].cancel_goal_async(), timeout)
        return {"cancelling": len(answer.goals_canceling)}

    def env(self) -> dict[str, Any]:
        return {"env": {name: os.environ.get(name) for name in
                        ("ROS_DOMAIN_ID", "ROS_AUTOMATIC_DISCOVERY_RANGE", "RMW_IMPLEMENTATION")}}


STATUS = {GoalStatus.STATUS_SUCCEEDED: "succeeded", GoalStatus.STATUS_CANCELED: "canceled",
          GoalStatus.STATUS_ABORTED: "aborted", GoalStatus.STATUS_ACCEPTED: "accepted",
          GoalStatus.STATUS_EXECUTING: "executing", GoalStatus.STATUS_CANCELING: "canceling"}


def main() -> int:
    rclpy.init()
    probe = Probe()
    print(json.dumps({"ok": True, "ready": True}), flush=True)
    for line in sys.stdin:
        command = json.loads(line)
        op = command.pop("op")
        if op == "quit":
            break
        if "uuid" in command:
            command["uuid_hex"] = command.pop("uuid")
        try:
            answer = {"ok": True, **getattr(probe, op)(**command)}
        except (TimeoutError, AttributeError, KeyError, TypeError, ValueError, AssertionError) as exc:
            answer = {"ok": False, "error": f"{type(exc).__name__}: {exc}"}
        print(json.dumps(answer), flush=True)
    probe.executor.shutdown(timeout_sec=2)
    probe.node.destroy_node()
    rclpy.shutdown()
    # rclpy's executor threads may still be winding down: leave without running their destructors
    # (a C++ std::thread destroyed while joinable aborts the process).
    os._exit(0)


if __name__ == "__main__":
    sys.exit(main())
