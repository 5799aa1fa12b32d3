"""Every intent the service emits, on ``/intents`` (hri_actions_msgs/Intent), in order.

The node reads the service's intent bus (dialogue.pushed) as the intent stream's clients do: the
intents of every dialogue turn — over ROS, REST, Rasa, a 4.0 stateless turn — and of the robot's
initiative (engage, greet), numbered once, in the bus's order. It reads from the start of this run's
buffer, so the intents of the moments before the node was up are published too; a reader that
falls behind is ended by the bus and resumes after the last intent it published (from the buffer;
a gap is logged). A read replica has no bus: its intents are on its writer's ``/intents``.

``communication_hub`` publishes the intents a chatbot returns on ``/intents`` itself: behind it,
remap ours (``-r /intents:=/situated/intents``) so that the mission controller does not get them twice.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
from collections.abc import Callable
from concurrent.futures import CancelledError
from concurrent.futures import TimeoutError as FutureTimeout
from typing import Any

from hri_actions_msgs.msg import Intent as IntentMessage
from rclpy.qos import QoSProfile, QoSReliabilityPolicy

from api.ros.node.front import Front
from api.ros.node.messages import intent_message
from dialogue.pushed.bus import IntentBus, Reader

log = logging.getLogger("situated.ros")
#: The bus's reason for ending its readers when the service stops.
STOPPING = "service stopping"
QOS = QoSProfile(depth=100, reliability=QoSReliabilityPolicy.RELIABLE)


async def publish_all(bus: IntentBus, reader: Reader, publish: Callable[[Any], None]) -> None:
    """Publish what ``reader`` reads, then what the bus has after it, until the service stops."""
    last = 0
    while True:
        try:
            if reader.gap is not None:
                log.warning("/intents: intents %s to %s were no longer buffered and are not published",
                            reader.gap.first, reader.gap.last)
            while (event := await reader.next()) is not None:
                publish(intent_message(event.intent))
                last = event.seq
        finally:
            bus.close(reader)
        if reader.end_reason == STOPPING:
            return
        log.warning("/intents fell behind the intent bus (%s); resuming after intent %s", reader.end_reason,
                    last)
        reader = bus.subscribe(asyncio.get_running_loop(), after=last)


def attach(front: Front) -> Callable[[], None]:
    bus = front.services.bus
    if bus is None:
        log.info("a read replica: its intents are published on its writer's /intents")
        return lambda: None
    node = front.chatbot_node
    publisher = node.create_publisher(IntentMessage, "/intents", QOS)
    reader = bus.subscribe(front.loop, after=0)  # the whole of this run's buffer first
    task = asyncio.run_coroutine_threadsafe(publish_all(bus, reader, publisher.publish), front.loop)

    def detach() -> None:
        task.cancel()
        with contextlib.suppress(FutureTimeout, CancelledError):
            task.result(2)
        node.destroy_publisher(publisher)

    return detach
