"""knowledge_core's events on the ``/kb`` node: the ``events`` service (kb_msgs/Event), a topic
``/kb/events/<id>`` per subscription (``api.ros.eventtopics``), and ``active_concepts``
(kb_msgs/ActiveConcepts), published whenever the set of active concepts changes.

kb_msgs' Event response has no ``success`` or ``error_msg``: a refused request answers an empty
``id`` and ``topic``, as knowledge_core does, and the node logs why (on ``/rosout``).
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from kb_msgs.msg import ActiveConcepts
from kb_msgs.srv import Event
from rclpy.node import Node
from rclpy.qos import QoSDurabilityPolicy, QoSProfile
from std_msgs.msg import String

from api.errors import ApiError
from api.ros.bounds import RequestBounds
from api.ros.eventtopics import EventTopics, Sweeper
from api.ros.node.front import Front
from kb import KbError

#: Relative to the node's namespace: /kb/events/<id>, as knowledge_core names them.
EVENTS_NAMESPACE = "events/"
#: Reliable and volatile, as knowledge_core's (a few messages deep: triggers may come in a burst).
EVENT_QOS = QoSProfile(depth=16)
#: The current set, for a subscriber that comes later too (volatile subscribers, as knowledge_core's
#: client, are matched as well).
ACTIVE_QOS = QoSProfile(depth=1, durability=QoSDurabilityPolicy.TRANSIENT_LOCAL)


class RosTopic:
    """An event topic as an rclpy publisher of std_msgs/String."""

    def __init__(self, node: Node, sub_id: str) -> None:
        self._node = node
        self._publisher = node.create_publisher(String, EVENTS_NAMESPACE + sub_id, EVENT_QOS)

    @property
    def name(self) -> str:
        return str(self._publisher.topic_name)

    def subscribers(self) -> int:
        return int(self._publisher.get_subscription_count())

    def publish(self, data: str) -> None:
        self._publisher.publish(String(data=data))

    def close(self) -> None:
        self._node.destroy_publisher(self._publisher)


class ActiveConceptsTopic:
    """``active_concepts``: the KB's listener (the writer's thread) publishes until it is closed."""

    def __init__(self, node: Node) -> None:
        self._node = node
        self._publisher = node.create_publisher(ActiveConcepts, "active_concepts", ACTIVE_QOS)
        self._lock = threading.Lock()
        self._open = True

    def __call__(self, concepts: list[str]) -> None:
        with self._lock:
            if self._open:
                self._publisher.publish(ActiveConcepts(concepts=list(concepts)))

    def close(self) -> None:
        with self._lock:
            self._open = False
            self._node.destroy_publisher(self._publisher)


def attach(front: Front) -> Callable[[], None]:
    """The events service, its topics and the active concepts on the ``/kb`` node."""
    node = front.kb_node
    services = front.services
    bounds = RequestBounds(services.settings.limits)
    topics = EventTopics(services.hub, lambda sub_id: RosTopic(node, sub_id))

    def on_request(request: Any, response: Any) -> Any:
        patterns, models = list(request.patterns), list(request.models)
        try:
            bounds.check(patterns=patterns, models=models)
            topic = topics.subscribe(patterns, request.one_shot, models or None)
        except (KbError, ApiError) as exc:
            reason = exc.message if isinstance(exc, ApiError) else str(exc)
            node.get_logger().error(f"/kb/events refused {patterns!r}: {reason}")
            response.id, response.topic = "", ""
            return response
        response.id, response.topic = topic.sub_id, topic.topic.name
        return response

    service = node.create_service(Event, "events", on_request)
    # A thread of its own, not a ROS timer: it sleeps when there is nothing to do (a 20 ms rclpy
    # timer costs about 4% of a core).
    sweeper = Sweeper(topics)
    sweeper.start()
    active = ActiveConceptsTopic(node)
    unwatch = services.kb.on_active_concept(active)

    def detach() -> None:
        unwatch()
        active.close()
        node.destroy_service(service)
        sweeper.stop()
        topics.close()

    return detach
