"""The ROS 2 front of the service: its nodes on the app's services, spun off the event loop.

Two nodes, as the ROS4HRI pieces they stand in for: ``/kb/knowledge_core`` serves knowledge_core's
API (services relative to the ``/kb`` namespace, event topics under ``/kb/events/``) and
``/chatbot`` the chatbot's (``~/start_dialogue``, ``~/dialogue_interaction``, the locale services),
the intents out and the perception in. Each concern is a part (a small module with an ``attach``
function); their order is the ``PARTS`` table. The executor runs every callback on its own threads:
a KB call blocks there, never on the event loop, and a dialogue turn is handed to the loop.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import threading
from collections.abc import Callable, Coroutine
from concurrent.futures import TimeoutError as FutureTimeout
from dataclasses import dataclass, field
from typing import Any, Protocol, TypeVar

import rclpy
from rcl_interfaces.msg import SetParametersResult
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import ExternalShutdownException, MultiThreadedExecutor
from rclpy.node import Node
from rclpy.signals import SignalHandlerOptions

from api.ros.parameters import NodeParameters, declare, refusal
from api.services import Services

log = logging.getLogger("situated.ros")

T = TypeVar("T")


class Part(Protocol):
    """One concern of the front: sets itself up on the front's nodes; returns what detaches it."""

    def __call__(self, front: Front) -> Callable[[], None]: ...


@dataclass
class Front:
    """What every part works with: the nodes, the service's own objects and the app's loop."""

    services: Services
    loop: asyncio.AbstractEventLoop
    context: Any
    kb_node: Node
    chatbot_node: Node
    parameters: NodeParameters
    #: Callbacks may run at the same time (a turn must not hold up a KB query).
    group: ReentrantCallbackGroup = field(default_factory=ReentrantCallbackGroup)

    def default_locale(self) -> str | None:
        """The node's default locale now (``default_locale``, which changes while the node runs)."""
        value = self.chatbot_node.get_parameter("default_locale").value
        return str(value) if value else None

    def on_loop(self, coroutine: Coroutine[Any, Any, T], timeout: float) -> T:
        """Run ``coroutine`` on the app's event loop and wait for it (from an executor thread)."""
        future = asyncio.run_coroutine_threadsafe(coroutine, self.loop)
        try:
            return future.result(timeout)
        except FutureTimeout:
            future.cancel()
            raise


def _parts() -> tuple[Part, ...]:
    # Imported here: each part imports the generated interfaces, which exist only once ROS is set up.
    from api.ros.node import chatbot, diagnostics, engagement, events, intents, knowledge, locales, voices

    return (knowledge.attach, events.attach, intents.attach, chatbot.attach, locales.attach,
            engagement.attach, voices.attach, diagnostics.attach)


def init(ros_args: list[str]) -> Any:
    """A ROS context initialised with the node's ``--ros-args`` (parameters file, remappings...).
    The HTTP server handles SIGINT and SIGTERM: rclpy installs no signal handler of its own."""
    context = rclpy.Context()
    rclpy.init(args=["situated", *(["--ros-args", *ros_args] if ros_args else [])], context=context,
               signal_handler_options=SignalHandlerOptions.NO)
    return context


def extension(services: Services, loop: asyncio.AbstractEventLoop, *, context: Any,
              defaults: NodeParameters, parts: tuple[Part, ...] | None = None) -> Callable[[], None]:
    """The app extension (``api.app.Extension``): create the nodes and their parts on ``context``
    and spin them on a thread; return what stops them (and shuts the context down)."""
    kb_node = Node("knowledge_core", namespace="kb", context=context)
    chatbot_node = Node("chatbot", context=context)
    front = Front(services, loop, context, kb_node, chatbot_node, declare(chatbot_node, defaults))
    chatbot_node.add_on_set_parameters_callback(_checked_change)
    detach = [attach(front) for attach in (parts if parts is not None else _parts())]
    executor = MultiThreadedExecutor(num_threads=4, context=context)
    executor.add_node(kb_node)
    executor.add_node(chatbot_node)
    thread = threading.Thread(target=_spin, args=(executor,), name="ros-executor", daemon=True)
    thread.start()
    log.info("ROS 2 node up: /kb/knowledge_core and /chatbot (domain %s)", context.get_domain_id())

    def stop() -> None:
        for undo in reversed(detach):
            undo()
        executor.shutdown(timeout_sec=5)
        thread.join(5)
        kb_node.destroy_node()
        chatbot_node.destroy_node()
        if context.ok():
            rclpy.shutdown(context=context)

    return stop


def _checked_change(changes: list[Any]) -> SetParametersResult:
    """Only what changes while the node runs (``default_locale``) may change, to a value it can use."""
    for change in changes:
        why = refusal(change.name, change.value)
        if why is not None:
            return SetParametersResult(successful=False, reason=why)
    return SetParametersResult(successful=True)


def _spin(executor: MultiThreadedExecutor) -> None:
    # The context shut down under the executor: the process is stopping.
    with contextlib.suppress(ExternalShutdownException):
        executor.spin()
