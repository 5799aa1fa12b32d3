"""``KB``: knowledge_core 3.5's Python client of its ROS API (``knowledge_core.api.KB``), for
situated's node (``situated ros run``) or knowledge_core's own.

The same calls as knowledge_core's (``find``, ``kb[...]``, ``+=``, ``-=``, ``in``, ``about``,
``label``, ``details``, ``lookup``, ``revise``, ``update``, ``remove``, ``subscribe``,
``on_active_concept``, ``clear``, ``hello``, ``stats``) and the same answers, without its
defects: a literal in ``kb[...]`` keeps its quotes (kb-compat K2), ``exist`` honours its models
(K7), ``label`` returns the label in the language asked (K6, read from ``/kb/details``), and a
refusal is always a ``KbError`` saying why (knowledge_core's ``clear`` and ``subscribe`` ignore
theirs). Usage, in a ROS 2 environment where the KB's node runs::

    import rclpy
    from api.ros.client.kb import KB

    rclpy.init()
    kb = KB()                       # or KB(node): the client then lives in that node's context
    kb += ["ari rdf:type Robot"]
    kb["* rdf:type Robot"]          # [{'var1': 'ari'}]
    kb.subscribe(["?r rdf:type Robot"], print)

The client answers its calls on a node and executor thread of its own, in the context of the node
it is given (whether or not that node is spun, from any thread, event callbacks included); event
and active-concept callbacks run on that thread. Every call waits at most ``timeout`` seconds.
"""

from __future__ import annotations

import contextlib
import json
import logging
import threading
import uuid
from collections.abc import Callable, Sequence
from typing import Any, Self

import rclpy
from builtin_interfaces.msg import Duration
from kb_msgs.msg import ActiveConcepts
from kb_msgs.srv import About, Event, Lookup, Manage, Query, Revise
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import ExternalShutdownException, MultiThreadedExecutor
from rclpy.node import Node
from std_msgs.msg import String

from api.ros.client.patterns import Find, anonymous, item, named_variables

log = logging.getLogger("situated.ros.client")

#: Seconds to wait for the KB's services, and for each answer.
DEFAULT_TIMEOUT = 60.0
KEEP_DEFAULTS = "keep_defaults"
Statements = str | Sequence[str]
Models = Sequence[str] | None
SERVICES = {"manage": Manage, "revise": Revise, "query": Query, "about": About, "label": About,
            "details": About, "lookup": Lookup, "events": Event}


class KbError(Exception):
    """A refusal of the KB (its ``error_msg``), or no answer in time. As knowledge_core's: the
    message is ``value``."""

    def __init__(self, value: Any) -> None:
        super().__init__(value)
        self.value = value

    def __str__(self) -> str:
        return repr(self.value)


def _list(statements: str | Sequence[str]) -> list[str]:
    return [statements] if isinstance(statements, str) else list(statements)


def _seconds(seconds: float) -> Duration:
    whole = int(seconds)
    return Duration(sec=whole, nanosec=round((seconds - whole) * 1e9))


class KB:
    """knowledge_core's ``KB(node=None)``; ``namespace`` is where the KB's services are (``/kb``)."""

    def __init__(self, node: Node | None = None, *, namespace: str = "/kb",
                 timeout: float = DEFAULT_TIMEOUT) -> None:
        context = node.context if node is not None else None
        if context is None and not rclpy.ok():
            rclpy.init()
        self.timeout = timeout
        self._namespace = namespace.rstrip("/")
        self._node = Node(f"kb_client_{uuid.uuid4().hex[:12]}", context=context)
        self._group = ReentrantCallbackGroup()
        # Two threads at least: an event callback that calls the KB gets its answer on the other.
        self._executor = MultiThreadedExecutor(num_threads=2, context=self._node.context)
        self._executor.add_node(self._node)
        self._thread = threading.Thread(target=self._spin, name="kb-client", daemon=True)
        self._thread.start()
        self._clients = {name: self._node.create_client(kind, f"{self._namespace}/{name}",
                                                        callback_group=self._group)
                         for name, kind in SERVICES.items()}
        self._lock = threading.Lock()
        self._events: dict[str, tuple[Any, list[Callable[[Any], None]]]] = {}
        self._active: Any = None
        self._active_callbacks: list[Callable[[list[str]], None]] = []
        self._closed = False
        for name, client in self._clients.items():
            if not client.wait_for_service(timeout_sec=timeout):
                self.close()
                raise KbError(f"the KB's service {self._namespace}/{name} is not available "
                              f"(waited {timeout:g} s): is its node running, on this ROS domain?")

    def _spin(self) -> None:
        with contextlib.suppress(ExternalShutdownException):  # the context shut down: the process stops
            self._executor.spin()

    # --- lifetime ---------------------------------------------------------------------------------

    def close(self) -> None:
        """Stop the client's thread and node (its event subscriptions end with them)."""
        if self._closed:
            return
        self._closed = True
        self._executor.shutdown(timeout_sec=5)
        self._thread.join(5)
        self._node.destroy_node()

    def __enter__(self) -> Self:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # --- calls ------------------------------------------------------------------------------------

    def _call(self, service: str, request: Any) -> Any:
        client = self._clients[service]
        if not client.service_is_ready() and not client.wait_for_service(timeout_sec=self.timeout):
            raise KbError(f"the KB's service {self._namespace}/{service} is not available")
        future = client.call_async(request)
        done = threading.Event()
        future.add_done_callback(lambda _: done.set())
        if not done.wait(self.timeout):
            client.remove_pending_request(future)
            raise KbError(f"no answer from {self._namespace}/{service} within {self.timeout:g} s")
        return future.result()

    def _json(self, service: str, request: Any) -> Any:
        answer = self._call(service, request)
        if not answer.success:
            raise KbError(answer.error_msg)
        return json.loads(answer.json) if answer.json else None

    def _revise(self, method: str, statements: str | Sequence[str], models: Sequence[str] | None,
                lifespan: float = 0) -> None:
        answer = self._call("revise", Revise.Request(method=method, statements=_list(statements),
                                                     models=list(models or []), lifespan=_seconds(lifespan)))
        if not answer.success:
            raise KbError(answer.error_msg)

    # --- management -------------------------------------------------------------------------------

    def stats(self) -> dict[str, Any]:
        """``{"name", "version", "reasoning_enabled", ...}``."""
        status: dict[str, Any] = self._json("manage", Manage.Request(action=Manage.Request.STATUS))
        return status

    def hello(self) -> str:
        return str(self.stats()["name"])

    def clear(self, keep_defaults: bool = False) -> None:
        """Empty the KB, as knowledge_core's ``clear`` does: its ontology too, unless
        ``keep_defaults``."""
        self._json("manage", Manage.Request(action=Manage.Request.CLEAR,
                                            parameters=[KEEP_DEFAULTS] if keep_defaults else []))

    # --- reads ------------------------------------------------------------------------------------

    def find(self, patterns: str | Sequence[str], vars: Sequence[str] | None = None,
             models: Sequence[str] | None = None) -> list[Any]:
        """Rows of bindings (``*`` is an anonymous variable); for ground patterns, the patterns
        if they hold, else ``[]``."""
        rows: list[Any] = self._json("query", Query.Request(patterns=anonymous(_list(patterns)),
                                                            vars=list(vars or []), models=list(models or [])))
        return rows

    def exist(self, patterns: str | Sequence[str], models: Sequence[str] | None = None) -> bool:
        return bool(self.find(patterns, None, models))

    def about(self, term: str, models: Sequence[str] | None = None) -> list[list[Any]]:
        found: list[list[Any]] = self._json("about", About.Request(term=term, models=list(models or [])))
        return found

    def details(self, term: str, models: Sequence[str] | None = None) -> dict[str, Any]:
        found: dict[str, Any] = self._json("details", About.Request(term=term, models=list(models or [])))
        return found

    def label(self, term: str, lang: str | None = None, models: Sequence[str] | None = None) -> str:
        """The term's label in ``lang`` if it has one, else its default label (else its name)."""
        labels = self.details(term, models)["label"]
        return str(labels.get(lang, labels["default"]) if lang is not None else labels["default"])

    def lookup(self, query: str, models: Sequence[str] | None = None) -> list[list[str]]:
        found: list[list[str]] = self._json("lookup", Lookup.Request(query=query, models=list(models or [])))
        return found

    def __getitem__(self, key: Any) -> list[Any]:
        """``kb["* rdf:type Robot"]``, ``kb["?a desires ?x", "?x rdf:type Action"]``,
        ``kb["s p o", ["model1"]]`` (a pattern: rows, or the pattern if it holds), or
        ``kb["a label"]`` (anything else: the ids its lookup finds)."""
        asked = item(key)
        if isinstance(asked, Find):
            return self.find(asked.patterns, named_variables(asked.patterns), asked.models)
        return [found[0] for found in self.lookup(asked.text, asked.models)]

    def __contains__(self, pattern: str) -> bool:
        """``"s p o" in kb`` (``*`` allowed): the pattern holds; ``"text" in kb``: lookup finds it."""
        asked = item(pattern)
        if isinstance(asked, Find):
            return self.exist(asked.patterns)
        return bool(self.lookup(asked.text))

    # --- writes -----------------------------------------------------------------------------------

    def update(self, stmts: Statements, models: Models = None, lifespan: float = 0) -> None:
        self._revise(Revise.Request.UPDATE, stmts, models, lifespan)

    def add(self, stmts: Statements, models: Models = None, lifespan: float = 0) -> None:
        self.update(stmts, models, lifespan)

    def remove(self, stmts: Statements, models: Models = None) -> None:
        self._revise(Revise.Request.REMOVE, stmts, models)

    def revise(self, stmts: Statements, policy: dict[str, Any]) -> None:
        """``policy``: ``method`` (update/add, retract/remove...), ``models``, ``lifespan``."""
        self._revise(str(policy.get("method", "")), stmts, policy.get("models"),
                     float(policy.get("lifespan", 0)))

    def __iadd__(self, stmts: Statements) -> Self:
        self.update(stmts)
        return self

    def __isub__(self, stmts: Statements) -> Self:
        self.remove(stmts)
        return self

    # --- events -----------------------------------------------------------------------------------

    def subscribe(self, pattern: str | Sequence[str], callback: Callable[[Any], None], one_shot: bool = False,
                  models: Sequence[str] | None = None) -> str:
        """Call ``callback(rows)`` with each trigger's new rows; returns the event id. The same
        callback subscribed again to the same event is called once per trigger."""
        answer = self._call("events", Event.Request(patterns=anonymous(_list(pattern)), one_shot=one_shot,
                                                    models=list(models or [])))
        if not answer.id:
            raise KbError(f"the KB refused the subscription to {_list(pattern)!r} (its node's log says why)")
        with self._lock:
            if answer.id not in self._events:
                callbacks: list[Callable[[Any], None]] = []
                relay = self._relay(answer.id, callbacks)
                subscription = self._node.create_subscription(String, answer.topic, relay, 10,
                                                              callback_group=self._group)
                self._events[answer.id] = (subscription, callbacks)
            _, callbacks = self._events[answer.id]
            if callback in callbacks:
                log.warning("event %s: already subscribed with this callback", answer.id)
            else:
                callbacks.append(callback)
        return str(answer.id)

    def _relay(self, event_id: str, callbacks: list[Callable[[Any], None]]) -> Callable[[Any], None]:
        def relay(message: Any) -> None:
            rows = json.loads(message.data)
            with self._lock:
                current = list(callbacks)
            for callback in current:
                callback(rows)
        return relay

    def unsubscribe(self, event_id: str) -> bool:
        """Stop listening to an event (the KB then ends it, nobody listening); False if unknown."""
        with self._lock:
            found = self._events.pop(event_id, None)
        if found is not None:
            self._node.destroy_subscription(found[0])
        return found is not None

    def on_active_concept(self, callback: Callable[[list[str]], None]) -> None:
        """Call ``callback(concepts)`` whenever the set of active concepts changes."""
        with self._lock:
            self._active_callbacks.append(callback)
            if self._active is None:
                self._active = self._node.create_subscription(
                    ActiveConcepts, f"{self._namespace}/active_concepts", self._on_active, 1,
                    callback_group=self._group)

    def _on_active(self, message: Any) -> None:
        with self._lock:
            current = list(self._active_callbacks)
        for callback in current:
            callback(list(message.concepts))
