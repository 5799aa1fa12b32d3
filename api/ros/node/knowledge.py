"""knowledge_core's ROS API on the service's KB (kb_msgs; knowledge_core 3.5's names under ``/kb``).

Every service answers ``success`` and, on a refusal, ``error_msg`` (a refused write changed
nothing), within the same limits as REST (patterns, statements, models, the text a request
carries, rows, query time). ``label`` answers the labels by language, which knowledge_core's client
reads there (knowledge_core serves the details, which that client cannot read: kb-compat K6).
Manage ``clear`` does what kb_msgs documents and knowledge_core does: the KB is emptied, its
ontology too, unless ``parameters`` holds ``keep_defaults`` (the service's REST and Python ``clear``
keep the ontology unless told not to).
"""

from __future__ import annotations

import json
from collections.abc import Callable, Sequence
from typing import Any

from kb_msgs.srv import About, Lookup, Manage, Query, Revise, Sparql
from std_msgs.msg import String

from api.errors import ApiError
from api.ros.bounds import RequestBounds
from api.ros.node.front import Front
from api.routes.health import package_version
from api.settings import Settings
from kb import KbError
from kb.protocol import KnowledgeBase

#: What a refused request answers in its error_msg: the KB's own refusals, and the service's limits.
REFUSALS = (KbError, ApiError)
#: Manage ``clear``'s one parameter (kb_msgs): keep the default ontology.
KEEP_DEFAULTS = "keep_defaults"


def _models(models: Sequence[str]) -> list[str] | None:
    """An empty list (ROS's unset array) is the robot's own model, as knowledge_core reads it."""
    return list(models) or None


def _seconds(duration: Any) -> float:
    return float(duration.sec) + float(duration.nanosec) / 1e9


class KnowledgeServices:
    """The handlers: a request in, the response filled (success, json, error_msg)."""

    def __init__(self, kb: KnowledgeBase, settings: Settings, clear: Callable[[bool], None]) -> None:
        self.kb = kb
        self.limits = settings.limits
        self.bounds = RequestBounds(settings.limits)
        self._check = self.bounds.check
        self._clear = clear

    def _answer(self, response: Any, work: Callable[[], Any], with_json: bool = True) -> Any:
        try:
            result = work()
        except REFUSALS as exc:
            response.success = False
            response.error_msg = exc.message if isinstance(exc, ApiError) else str(exc)
            return response
        response.success = True
        response.error_msg = ""
        if with_json:
            response.json = json.dumps(result)
        return response

    def query(self, request: Any, response: Any) -> Any:
        def work() -> Any:
            self._check(patterns=request.patterns, models=request.models)
            return self.kb.find(list(request.patterns), list(request.vars) or None, _models(request.models),
                                max_rows=self.limits.max_rows, timeout=self.limits.query_timeout)
        return self._answer(response, work)

    def revise(self, request: Any, response: Any) -> Any:
        def work() -> None:
            self._check(statements=request.statements, models=request.models)
            policy = {"method": request.method, "models": _models(request.models),
                      "lifespan": _seconds(request.lifespan)}
            self.kb.revise(list(request.statements), policy)
        return self._answer(response, work, with_json=False)

    def about(self, request: Any, response: Any) -> Any:
        return self._answer(response, lambda: self.kb.about(*self._term(request)))

    def details(self, request: Any, response: Any) -> Any:
        return self._answer(response, lambda: self.kb.details(*self._term(request)))

    def label(self, request: Any, response: Any) -> Any:
        """The term's labels by language, ``{"default": ..., "fr": ...}``: what knowledge_core's
        client reads from ``/kb/label`` (its server answers the details there, which that client
        cannot read: kb-compat K6)."""
        return self._answer(response, lambda: self.kb.details(*self._term(request))["label"])

    def lookup(self, request: Any, response: Any) -> Any:
        def work() -> Any:
            self._check(models=request.models, texts=[request.query])
            return self.kb.lookup(request.query, _models(request.models))
        return self._answer(response, work)

    def _term(self, request: Any) -> tuple[str, list[str] | None]:
        self._check(models=request.models, texts=[request.term])
        return request.term, _models(request.models)

    def sparql(self, request: Any, response: Any) -> Any:
        def work() -> Any:
            self._check(models=request.models, texts=[request.query])
            return self.kb.sparql(request.query, _models(request.models), timeout=self.limits.query_timeout,
                                  max_rows=self.limits.max_rows)
        return self._answer(response, work)

    def manage(self, request: Any, response: Any) -> Any:
        action = MANAGE.get(request.action)
        if action is None:
            response.success = False
            response.error_msg = (f"unknown 'manage' action {request.action!r}: one of "
                                  + ", ".join(sorted(MANAGE)))
            return response
        def work() -> Any:
            self._check(models=request.models, texts=request.parameters)
            return action(self, list(request.parameters), _models(request.models))
        return self._answer(response, work)

    def fact(self, statement: str, method: str) -> None:
        """One statement of the add_fact / remove_fact topics."""
        self._check(statements=[statement])
        self.kb.revise([statement], {"method": method})

    # --- manage actions --------------------------------------------------------------------------------

    def _do_clear(self, parameters: list[str], models: list[str] | None) -> None:
        if parameters not in ([], [KEEP_DEFAULTS]):
            raise KbError(f"'clear' takes no parameter (everything goes, the ontology too) or "
                          f"[{KEEP_DEFAULTS!r}] (the ontology stays), got {parameters!r}")
        self._clear(KEEP_DEFAULTS in parameters)

    def _do_load(self, parameters: list[str], models: list[str] | None) -> None:
        if len(parameters) != 1:
            raise KbError("'load' expects 'parameters' to hold exactly one URI of the ontology to load")
        self.kb.load(parameters[0], models)

    def _do_save(self, parameters: list[str], models: list[str] | None) -> list[str]:
        if len(parameters) != 2:
            raise KbError("'save' expects 'parameters' to hold exactly two values: the folder and the "
                          "basename (one RDF/XML file per model: <folder>/<basename>-<model>.rdf)")
        return self.kb.save(parameters[0], parameters[1], models)

    def _do_status(self, parameters: list[str], models: list[str] | None) -> dict[str, Any]:
        summary = self.kb.summary()
        return {"name": "situated", "version": package_version(), "reasoning_enabled": True,
                "revision": summary.revision, "models": list(summary.models)}


#: knowledge_core's Manage actions.
MANAGE: dict[str, Callable[[KnowledgeServices, list[str], list[str] | None], Any]] = {
    Manage.Request.CLEAR: KnowledgeServices._do_clear,
    Manage.Request.LOAD: KnowledgeServices._do_load,
    Manage.Request.SAVE: KnowledgeServices._do_save,
    Manage.Request.STATUS: KnowledgeServices._do_status,
}


def attach(front: Front) -> Callable[[], None]:
    """knowledge_core's services and fact topics on the ``/kb`` node."""
    node = front.kb_node
    handlers = KnowledgeServices(front.services.kb, front.services.settings, front.services.clear)
    table = (("manage", Manage, handlers.manage), ("revise", Revise, handlers.revise),
             ("query", Query, handlers.query), ("about", About, handlers.about),
             ("label", About, handlers.label), ("details", About, handlers.details),
             ("lookup", Lookup, handlers.lookup), ("sparql", Sparql, handlers.sparql))
    made = [node.create_service(kind, name, handler)
            for name, kind, handler in table]

    def fact(method: str) -> Callable[[Any], None]:
        def on_message(message: Any) -> None:
            response = Revise.Response()
            handlers._answer(response, lambda: handlers.fact(message.data, method), with_json=False)
            if not response.success:
                node.get_logger().error(f"/kb/{method} of {message.data!r} refused: {response.error_msg}")
        return on_message

    subscriptions = [node.create_subscription(String, topic, fact(method), 10)
                     for topic, method in (("add_fact", "update"), ("remove_fact", "retract"))]

    def detach() -> None:
        for service in made:
            node.destroy_service(service)
        for subscription in subscriptions:
            node.destroy_subscription(subscription)

    return detach
