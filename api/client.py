"""A small synchronous client of a running service, for the CLI's ``--url`` mode.

Its methods mirror the library's (``KB.find``, ``KB.revise``...), so CLI commands run the same
code against an in-process KB or a remote service.
"""

from __future__ import annotations

from typing import Any

import httpx


class ClientError(RuntimeError):
    """The service refused the request or could not be reached; the message says why."""


class ServiceClient:
    def __init__(self, url: str, token: str | None = None, timeout: float = 30.0) -> None:
        headers = {"authorization": f"Bearer {token}"} if token else {}
        self._http = httpx.Client(base_url=url.rstrip("/"), headers=headers, timeout=timeout)

    def close(self) -> None:
        self._http.close()

    def __enter__(self) -> ServiceClient:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _call(self, method: str, path: str, **kwargs: Any) -> Any:
        try:
            response = self._http.request(method, path, **kwargs)
        except httpx.HTTPError as exc:
            raise ClientError(f"cannot reach {self._http.base_url}: {exc}") from exc
        if response.is_error:
            try:
                body = response.json()
                message = body["message"] if isinstance(body, dict) and "message" in body else response.text
            except ValueError:
                message = response.text
            raise ClientError(f"HTTP {response.status_code}: {message}")
        return response.json() if response.content else None

    # --- the KB methods the CLI uses -------------------------------------------------------------

    def find(self, patterns: list[str], vars: list[str] | None = None,
             models: list[str] | None = None) -> list[Any]:
        result: list[Any] = self._call("POST", "/kb/query",
                                       json={"patterns": patterns, "vars": vars, "models": models})
        return result

    def revise(self, stmts: list[str], policy: dict[str, Any]) -> int | None:
        """Returns the number of asserted triples a retraction removed (None for an addition)."""
        answer = self._call("POST", "/kb/revise", json={"statements": stmts, **policy})
        removed: int | None = answer["removed"]
        return removed

    def details(self, term: str, models: list[str] | None = None) -> dict[str, Any]:
        result: dict[str, Any] = self._call("GET", f"/kb/details/{term}", params={"models": models or []})
        return result

    def lookup(self, query: str, models: list[str] | None = None) -> list[list[str]]:
        result: list[list[str]] = self._call("GET", "/kb/lookup", params={"q": query, "models": models or []})
        return result

    # --- dialogue ------------------------------------------------------------------------------

    def start_dialogue(self) -> str:
        dialogue_id: str = self._call("POST", "/dialogues", json={})["dialogue_id"]
        return dialogue_id

    def interact(self, dialogue_id: str, user_id: str, text: str) -> dict[str, Any]:
        result: dict[str, Any] = self._call("POST", f"/dialogues/{dialogue_id}/interactions",
                                            json={"user_id": user_id, "input": text})
        return result
