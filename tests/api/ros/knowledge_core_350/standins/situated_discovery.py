"""A pytest plugin (``-p situated_discovery``): DDS discovery gets the time it takes on this machine.

knowledge_core's tests give a client 1 s to discover a service (``wait_for_service(timeout_sec=1.0)``,
right after creating it). The discovery of a new endpoint over Fast DDS here takes from a few
milliseconds to about 3 s, even once the KB's node is known (measured: 0.0-3.0 s), so those tests
would fail on the transport before any assertion about the KB. This plugin lets every
``wait_for_service`` wait at least ``DISCOVERY`` seconds; a service that never comes still fails
the test, later. Nothing else of rclpy, and no assertion, changes.
"""

from __future__ import annotations

from typing import Any

from rclpy.client import Client

#: Seconds a client may take to discover a service.
DISCOVERY = 30.0
_wait_for_service = Client.wait_for_service


def _patient(self: Client, timeout_sec: float | None = None) -> bool:
    if timeout_sec is not None and timeout_sec >= 0:
        timeout_sec = max(timeout_sec, DISCOVERY)
    return bool(_wait_for_service(self, timeout_sec))


def pytest_configure(config: Any) -> None:
    Client.wait_for_service = _patient  # type: ignore[method-assign]
