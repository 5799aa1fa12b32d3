"""A SPARQL 1.1 Protocol client: the connection to the store a scaled-out KB lives in.

The store is named by one URL, ``sparql+http://HOST:PORT[/BASE][?query=..&update=..&dataset=..]``.
By default queries go to ``BASE/query`` and updates to ``BASE/update`` (Oxigraph's layout, and
Fuseki's with ``BASE`` the dataset path); ``query=`` and ``update=`` give other paths or URLs
(GraphDB: ``/repositories/R`` and ``/repositories/R/statements``; Virtuoso: ``/sparql`` for
both). ``dataset=`` chooses the graphs of kb.layout (default ``situated``).

One keep-alive HTTP connection pool serves every thread; each call is one request.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from contextlib import closing
from dataclasses import dataclass
from typing import Any
from urllib.parse import parse_qs, urljoin, urlsplit, urlunsplit

import httpx
from rdflib import BNode, Literal, URIRef

from kb.deadline import Deadline, QueryTimeout
from kb.errors import KbError
from kb.layout import Layout, unskolem
from kb.terms import Node

RESULTS_JSON = "application/sparql-results+json"


class StoreUnavailable(KbError):
    """The SPARQL store could not be reached or failed the request; nothing was changed by it."""


@dataclass(frozen=True)
class StoreSpec:
    query_url: str
    update_url: str
    layout: Layout

    @classmethod
    def parse(cls, spec: str) -> StoreSpec:
        parts = urlsplit(spec)
        if parts.scheme not in ("sparql+http", "sparql+https") or not parts.netloc:
            raise KbError(f"store {spec!r} must look like sparql+http://HOST:PORT[/BASE]")
        options = parse_qs(parts.query)
        unknown = set(options) - {"query", "update", "dataset"}
        if unknown:
            raise KbError(f"store {spec!r}: unknown option(s) {sorted(unknown)}; use query, update, dataset")
        scheme = parts.scheme.removeprefix("sparql+")
        base = urlunsplit((scheme, parts.netloc, parts.path.rstrip("/"), "", ""))

        def endpoint(name: str) -> str:
            given = options.get(name, [""])[-1]
            return urljoin(base + "/", given) if given else f"{base}/{name}"

        return cls(endpoint("query"), endpoint("update"), Layout(options.get("dataset", ["situated"])[-1]))


class SparqlEndpoint:
    """Queries and updates against one SPARQL 1.1 server."""

    def __init__(self, spec: StoreSpec | str, timeout: float = 30.0, *,
                 http: httpx.Client | None = None) -> None:
        """``http``: a client (connection pool) to share with other endpoints of the same server;
        it stays the caller's to close."""
        self.spec = spec if isinstance(spec, StoreSpec) else StoreSpec.parse(spec)
        self._own_http = http is None
        self._http = http if http is not None else httpx.Client(
            timeout=timeout, limits=httpx.Limits(max_keepalive_connections=16))

    @property
    def layout(self) -> Layout:
        return self.spec.layout

    def close(self) -> None:
        if self._own_http:
            self._http.close()

    def select(self, query: str, deadline: Deadline | None = None) -> list[dict[str, Node]]:
        """The rows of a SELECT query, as rdflib terms (unbound variables left out)."""
        body = json.loads(self._query(query, RESULTS_JSON, deadline=deadline)[1])
        # Large answers repeat a few terms many times (a graph name, a predicate, a class):
        # building each rdflib term once costs less than looking the JSON value up.
        seen: dict[tuple[str | None, ...], Node] = {}
        rows = []
        for row in body["results"]["bindings"]:
            out = {}
            for name, value in row.items():
                key = (value["type"], value["value"], value.get("datatype"), value.get("xml:lang"))
                node = seen.get(key)
                if node is None:
                    node = seen[key] = _node(value)
                out[name] = node
            rows.append(out)
        return rows

    def ask(self, query: str, deadline: Deadline | None = None) -> bool:
        return bool(json.loads(self._query(query, RESULTS_JSON, deadline=deadline)[1])["boolean"])

    def raw(self, query: str, accept: str, default_graphs: list[str],
            deadline: Deadline | None = None) -> tuple[str, bytes]:
        """Any query, answered in the format ``accept`` names, over the given default graphs
        (SPARQL Protocol ``default-graph-uri``); returns (content type, body)."""
        return self._query(query, accept, default_graphs, deadline)

    def update(self, update: str) -> None:
        """One update request: the store applies all of it or none of it."""
        self._send("POST", self.spec.update_url, content=update.encode(),
                   headers={"content-type": "application/sparql-update"})

    def _query(self, query: str, accept: str, default_graphs: list[str] | None = None,
               deadline: Deadline | None = None) -> tuple[str, bytes]:
        """The answer's content type and body; with a deadline, the request and the reading of the answer stop
        there (``QueryTimeout``; the store itself may go on with the query: SPARQL has no way
        to cancel one)."""
        form: dict[str, str | list[str]] = {"query": query}
        if default_graphs:
            form["default-graph-uri"] = default_graphs
        if deadline is None:
            response = self._send("POST", self.spec.query_url, data=form, headers={"accept": accept})
            return response.headers.get("content-type", accept), response.content
        request = self._http.build_request("POST", self.spec.query_url, data=form, headers={"accept": accept},
                                           timeout=deadline.remaining())
        try:
            response = self._checked(self.spec.query_url, lambda: self._http.send(request, stream=True))
            with closing(response):
                if response.is_error:
                    response.read()
                    self._refuse(self.spec.query_url, response)
                chunks = []
                for chunk in response.iter_bytes():
                    deadline.check()
                    chunks.append(chunk)
                return response.headers.get("content-type", accept), b"".join(chunks)
        except httpx.TimeoutException:
            raise QueryTimeout(deadline.seconds) from None
        except httpx.HTTPError as exc:
            raise StoreUnavailable(f"the SPARQL store at {self.spec.query_url} cannot be reached: "
                                   f"{exc}") from exc

    def _checked(self, url: str, send: Callable[[], httpx.Response]) -> httpx.Response:
        if self._http.is_closed:  # httpx would raise a bare RuntimeError
            raise StoreUnavailable(f"the connection to the SPARQL store at {url} was closed")
        return send()

    @staticmethod
    def _refuse(url: str, response: httpx.Response) -> None:
        raise StoreUnavailable(f"the SPARQL store at {url} answered {response.status_code}: "
                               f"{response.text[:300]}")

    def _send(self, method: str, url: str, **kwargs: Any) -> httpx.Response:
        try:
            response = self._checked(url, lambda: self._http.request(method, url, **kwargs))
        except httpx.HTTPError as exc:
            raise StoreUnavailable(f"the SPARQL store at {url} cannot be reached: {exc}") from exc
        if response.is_error:
            self._refuse(url, response)
        return response


def _node(value: dict[str, str]) -> Node:
    kind = value["type"]
    if kind == "uri":
        return unskolem(value["value"])
    if kind == "bnode":
        return BNode(value["value"])
    datatype = value.get("datatype")
    return Literal(value["value"], lang=value.get("xml:lang"),
                   datatype=URIRef(datatype) if datatype else None)
