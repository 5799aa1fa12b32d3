"""The one client of a running service's REST API, synchronous.

The CLI's ``--url`` mode reads and writes through it, and a reader process hands its writes to the
writer service through it (it is a ``kb.sparqlstore.writetarget.WriteTarget``). Its methods mirror
the library's (``KB.find``, ``KB.update``...), so the same code runs against an in-process KB or a
service. A refusal comes back as ``ClientError`` with the service's own status, code, message and
details, so a reader passes the writer's refusal on unchanged.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import httpx

from kb.arguments import Changes
from kb.formats import rdf_format
from kb.terms import as_list

Models = str | Sequence[str] | None


class ClientError(RuntimeError):
    """The service refused the request (its status, code, message and details) or could not be
    reached (503, ``<name>_unavailable``); ``str()`` says which."""

    def __init__(self, status: int, code: str, message: str, details: Any = None) -> None:
        super().__init__(f"HTTP {status}: {message}")
        self.status = status
        self.code = code
        self.message = message
        self.details = details


class ServiceClient:
    """``name`` says what the service is to this process ("service", "writer") in messages."""

    def __init__(self, url: str, token: str | None = None, timeout: float = 30.0, *,
                 name: str = "service", transport: httpx.BaseTransport | None = None) -> None:
        headers = {"authorization": f"Bearer {token}"} if token else {}
        self.url = url.rstrip("/")
        self.name = name
        self._http = httpx.Client(base_url=self.url, headers=headers, timeout=timeout, transport=transport)

    def close(self) -> None:
        self._http.close()

    def __enter__(self) -> ServiceClient:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _call(self, method: str, path: str, *, writes: bool = False, **kwargs: Any) -> Any:
        try:
            response = self._http.request(method, path, **kwargs)
        except httpx.HTTPError as exc:
            after = "; nothing was written" if writes else ""
            raise ClientError(503, f"{self.name}_unavailable", f"the {self.name} at {self.url} "
                              f"cannot be reached: {exc}{after}") from exc
        if response.is_error:
            raise _refusal(response, self.name)
        return response.json() if response.content else None

    # --- reads ---------------------------------------------------------------------------------

    def find(self, patterns: list[str], vars: list[str] | None = None,
             models: list[str] | None = None) -> list[Any]:
        result: list[Any] = self._call("POST", "/kb/query",
                                       json={"patterns": patterns, "vars": vars, "models": models})
        return result

    def details(self, term: str, models: list[str] | None = None) -> dict[str, Any]:
        result: dict[str, Any] = self._call("GET", f"/kb/details/{term}", params={"models": models or []})
        return result

    def lookup(self, query: str, models: list[str] | None = None) -> list[list[str]]:
        result: list[list[str]] = self._call("GET", "/kb/lookup", params={"q": query, "models": models or []})
        return result

    # --- writes (the write half of the KB API) -------------------------------------------------

    def revise(self, stmts: list[str], policy: dict[str, Any]) -> int | None:
        """Returns the number of asserted triples a retraction removed (None for an addition)."""
        answer = self._call("POST", "/kb/revise", writes=True, json={"statements": stmts, **policy})
        removed: int | None = answer["removed"]
        return removed

    def update(self, stmts: str | Sequence[str], models: Models = None, lifespan: float = 0) -> None:
        self._call("POST", "/kb/revise", writes=True, json={
            "statements": as_list(stmts), "method": "update", "models": _models(models),
            "lifespan": lifespan or None})

    def remove(self, stmts: str | Sequence[str], models: Models = None) -> int:
        answer = self._call("POST", "/kb/revise", writes=True, json={
            "statements": as_list(stmts), "method": "retract", "models": _models(models)})
        return int(answer["removed"])

    def apply(self, add: Sequence[str] = (), remove: Sequence[str] = (), models: Models = None,
              lifespan: float = 0) -> None:
        self._call("POST", "/kb/apply", writes=True, json={
            "add": as_list(add), "remove": as_list(remove), "models": _models(models),
            "lifespan": lifespan or None})

    def apply_models(self, changes: Mapping[str, Changes], lifespan: float = 0) -> None:
        self._call("POST", "/kb/apply_models", writes=True, json={
            "changes": {name: {"add": as_list(c.get("add", ())), "remove": as_list(c.get("remove", ()))}
                        for name, c in changes.items()},
            "lifespan": lifespan or None})

    def clear(self, keep_defaults: bool = True) -> None:
        self._call("POST", "/kb/clear", writes=True, json={"keep_defaults": keep_defaults})

    def load_data(self, data: str | bytes, fmt: str = "turtle", models: Models = None) -> None:
        body = data.encode() if isinstance(data, str) else data
        self._call("POST", "/kb/load", writes=True, content=body,
                   headers={"content-type": rdf_format(fmt).media_type},
                   params={"models": _models(models) or []})

    def sparql_update(self, update: str, models: Models = None) -> None:
        names = _models(models) or []
        self._call("POST", "/sparql", writes=True, data={"update": update},
                   params={"model": names[0]} if names else None)

    # --- intents -------------------------------------------------------------------------------

    def publish_intent(self, emitted: dict[str, Any]) -> int:
        """Push an emitted intent (``{"origin", "intent", "dialogue_id"?, "response"?, "time"?}``)
        on the service's intent stream; returns the number it was given."""
        seq: int = self._call("POST", "/intents", writes=True, json=emitted)["seq"]
        return seq

    # --- dialogue ------------------------------------------------------------------------------

    def start_dialogue(self) -> str:
        dialogue_id: str = self._call("POST", "/dialogues", json={})["dialogue_id"]
        return dialogue_id

    def start_role(self, role: str, configuration: str, locale: str | None = None) -> dict[str, Any]:
        """Start a dialogue with a role: ``{"dialogue_id", "response"?}`` (the opening line)."""
        body: dict[str, Any] = {"role": {"name": role, "configuration": configuration}}
        if locale:
            body["locale"] = locale
        started: dict[str, Any] = self._call("POST", "/dialogues", json=body)
        return started

    def interact(self, dialogue_id: str, user_id: str, text: str) -> dict[str, Any]:
        result: dict[str, Any] = self._call("POST", f"/dialogues/{dialogue_id}/interactions",
                                            json={"user_id": user_id, "input": text})
        return result


def _models(models: Models) -> list[str] | None:
    return as_list(models) if models else None


def _refusal(response: httpx.Response, name: str) -> ClientError:
    """The service's own error, as it is (its JSON error shape, or its status)."""
    try:
        body = response.json()
    except ValueError:
        body = None
    if isinstance(body, dict) and isinstance(body.get("message"), str):
        return ClientError(response.status_code, str(body.get("code") or f"{name}_error"), body["message"],
                           body.get("details"))
    return ClientError(response.status_code, f"{name}_error",
                       f"the {name} answered {response.status_code}: {response.text[:300]}")
