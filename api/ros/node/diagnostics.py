"""The service's health on ``/diagnostics`` (diagnostic_msgs/DiagnosticArray) every
``diagnostics_period`` seconds, as the tutorial's chatbot reports its own: the statuses of
api.ros.statuses (the service, the KB, the model, each component), from ``/health``'s report.

The report is made on the app's loop and published when it is done: the ``/chatbot`` node's thread
never waits for it (a model that does not answer takes the report seconds), and a report still
being made when the next is due is not doubled."""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from concurrent.futures import Future
from typing import Any

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue

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
    limit = max(period, 2.0)
    making: list[Future[Any]] = []

    async def report() -> dict[str, Any] | None:
        try:
            return await asyncio.wait_for(health_report(front.services, details=True), limit)
        except TimeoutError:
            log.warning("no /diagnostics this time: the health report took over %g s", limit)
            return None

    def publish(done: Future[dict[str, Any] | None]) -> None:
        made = None if done.cancelled() else done.result()
        if made is None:
            return
        array = DiagnosticArray(status=[message(status) for status in statuses(made)])
        array.header.stamp = node.get_clock().now().to_msg()
        publisher.publish(array)

    def due() -> None:
        if making and not making[-1].done():
            return  # a slow report never piles up
        making[:] = [asyncio.run_coroutine_threadsafe(report(), front.loop)]
        making[-1].add_done_callback(publish)

    timer = node.create_timer(period, due)

    def detach() -> None:
        timer.cancel()
        node.destroy_timer(timer)
        for pending in making:
            pending.cancel()
        node.destroy_publisher(publisher)

    return detach
