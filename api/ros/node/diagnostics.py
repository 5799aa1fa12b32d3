"""The service's health on ``/diagnostics`` (diagnostic_msgs/DiagnosticArray) every
``diagnostics_period`` seconds, as the tutorial's chatbot reports its own: the statuses of
api.ros.statuses (the service, the KB, the model, each component), from ``/health``'s report."""

from __future__ import annotations

import logging
from collections.abc import Callable
from concurrent.futures import TimeoutError as FutureTimeout

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup

from api.healthreport import health_report
from api.ros.node.front import Front
from api.ros.statuses import HARDWARE_ID, Status, statuses

log = logging.getLogger("situated.ros")


def message(status: Status) -> DiagnosticStatus:
    return DiagnosticStatus(level=bytes([status.level]), name=status.name, message=status.message,
                            hardware_id=HARDWARE_ID,
                            values=[KeyValue(key=key, value=value) for key, value in status.values])


def attach(front: Front) -> Callable[[], None]:
    node = front.chatbot_node
    period = front.parameters.diagnostics_period
    publisher = node.create_publisher(DiagnosticArray, "/diagnostics", 10)

    def publish() -> None:
        try:
            report = front.on_loop(health_report(front.services, details=True), max(period, 2.0))
        except FutureTimeout:
            log.warning("no /diagnostics this time: the health report took over %g s", max(period, 2.0))
            return
        array = DiagnosticArray(status=[message(status) for status in statuses(report)])
        array.header.stamp = node.get_clock().now().to_msg()
        publisher.publish(array)

    # One at a time: a slow report never piles up.
    timer = node.create_timer(period, publish, callback_group=MutuallyExclusiveCallbackGroup())

    def detach() -> None:
        timer.cancel()
        node.destroy_timer(timer)
        node.destroy_publisher(publisher)

    return detach
