"""The ROS 2 front of the service: its nodes on the app's services, spun off the event loop.

Two nodes, as the ROS4HRI pieces they stand in for: ``/kb/knowledge_core`` serves knowledge_core's
API (services relative to the ``/kb`` namespace, event topics under ``/kb/events/``) and
``/chatbot`` the chatbot's (``~/start_dialogue``, ``~/dialogue_interaction``, the locale services),
the intents out and the perception in. Each concern is a part (a small module with an ``attach``
function); their order is the ``PARTS`` table.

Each node has an executor of its own on a thread of its own, rclpy's ``EventsExecutor`` (its
callbacks run straight from the middleware's events, with no wait set rebuilt in Python per
callback, and no hand-off to a pool thread): a KB call runs on the ``/kb`` node's thread, never on
the event loop, and is never held up by a turn; a dialogue turn runs on the app's event loop, and its
callback awaits it (``Front.awaited``) without holding the ``/chatbot`` thread for longer than a slice.
"""

from __future__ import annotations

import asyncio
import logging
import threading
import time
from collections.abc import Callable, Coroutine, Generator
from concurrent.futures import Future
from concurrent.futures import TimeoutError as FutureTimeout
from dataclasses import dataclass
from typing import Any, Generic, Protocol, TypeVar

import rclpy
from rcl_interfaces.msg import SetParametersResult
from rclpy.experimental.events_executor import EventsExecutor
from rclpy.node import Node
from rclpy.signals import SignalHandlerOptions

from api.ros.parameters import NodeParameters, declare, refusal
from api.services import Services

log = logging.getLogger("situated.ros")

T = TypeVar("T")
#: Seconds an awaiting callback blocks its executor's thread at a time (``LoopResult``), and between
#: two looks of an executor's thread at whether it is to stop.
SLICE = 0.01
SPIN = 0.5


class LoopResult(Generic[T]):
    """What a coroutine run on the app's loop returns, awaited by a callback of an ``EventsExecutor``.

    That executor resumes a pending callback again at once, with no wake-up to wait for: awaiting a
    plain future would poll without pause. This waits for the result for up to ``SLICE`` seconds at
    each resumption, the GIL released: a turn done within a slice (the offline rules take a few ms)
    is answered at once, and while a slow one (a model) is awaited, the executor's other callbacks
    run between slices at little cost."""

    def __init__(self, future: Future[T], timeout: float) -> None:
        self.future = future
        self.end = time.monotonic() + timeout

    def __await__(self) -> Generator[None, None, T]:
        while True:
            left = self.end - time.monotonic()
            try:
                return self.future.result(max(0.0, min(SLICE, left)))
            except FutureTimeout:
                if left <= SLICE:
                    self.future.cancel()
                    raise
            yield


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

    def default_locale(self) -> str | None:
        """The node's default locale now (``default_locale``, which changes while the node runs)."""
        value = self.chatbot_node.get_parameter("default_locale").value
        return str(value) if value else None

    def awaited(self, coroutine: Coroutine[Any, Any, T], timeout: float) -> LoopResult[T]:
        """Run ``coroutine`` on the app's event loop; what an async callback awaits (``TimeoutError``
        after ``timeout`` s, the coroutine cancelled)."""
        return LoopResult(asyncio.run_coroutine_threadsafe(coroutine, self.loop), timeout)


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
    and spin each on a thread of its own; return what stops them (and shuts the context down)."""
    kb_node = Node("knowledge_core", namespace="kb", context=context)
    chatbot_node = Node("chatbot", context=context)
    front = Front(services, loop, context, kb_node, chatbot_node, declare(chatbot_node, defaults))
    chatbot_node.add_on_set_parameters_callback(_checked_change)
    detach = [attach(front) for attach in (parts if parts is not None else _parts())]
    spinners = [Spinner(node, context) for node in (kb_node, chatbot_node)]
    log.info("ROS 2 node up: /kb/knowledge_core and /chatbot (domain %s)", context.get_domain_id())

    def stop() -> None:
        for undo in reversed(detach):
            undo()
        for spinner in spinners:
            spinner.stop()
        kb_node.destroy_node()
        chatbot_node.destroy_node()
        if context.ok():
            rclpy.shutdown(context=context)

    return stop


class Spinner:
    """One node's ``EventsExecutor``, spun on a thread of its own until ``stop``."""

    def __init__(self, node: Node, context: Any) -> None:
        self.context = context
        self.executor = EventsExecutor(context=context)
        self.executor.add_node(node)
        self._stopping = threading.Event()
        self.thread = threading.Thread(target=self._spin, name=f"ros-{node.get_name()}", daemon=True)
        self.thread.start()

    def _spin(self) -> None:
        # One event at a time, bounded: the thread sees in time that the service stops (and in our
        # trials Kilted's rclpy 9.1.2 EventsExecutor ran no callback in spin(), but does in spin_once()).
        while not self._stopping.is_set() and self.context.ok():
            self.executor.spin_once(timeout_sec=SPIN)

    def stop(self) -> None:
        self._stopping.set()
        self.executor.shutdown(timeout_sec=5)
        self.thread.join(5)


def _checked_change(changes: list[Any]) -> SetParametersResult:
    """Only what changes while the node runs (``default_locale``) may change, to a value it can use."""
    for change in changes:
        why = refusal(change.name, change.value)
        if why is not None:
            return SetParametersResult(successful=False, reason=why)
    return SetParametersResult(successful=True)
