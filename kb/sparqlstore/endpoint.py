"""A SPARQL 1.1 Protocol client: the connection to the store a scaled-out KB lives in.

The store is named by one URL, ``sparql+http://HOST:PORT[/BASE][?query=..&update=..&dataset=..]``.
By default queries go to ``BASE/query`` and updates to ``BASE/update`` (Oxigraph's layout, and
Fuseki's with ``BASE`` the dataset path); ``query=`` and ``update=`` give other paths or URLs
(GraphDB: ``/repositories/R`` and ``/repositories/R/statements``; Virtuoso: ``/sparql`` for
both). ``dataset=`` chooses the graphs of kb.sparqlstore.layout (default ``situated``).

One keep-alive HTTP connection pool serves every thread; each call is one request, bounded by
the endpoint's timeout (or the one the call gives). An update that was sent but got no answer in
time raises ``OutcomeUnknown``: the store may have applied it, or may still apply it (a stalled
store that resumes processes what it had received), so its caller must find out (kb.sparqlstore.mirror).
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

from kb.deadline import Deadline
from kb.errors import KbError, OutcomeUnknown, QueryTimeout, StoreUnavailable
from kb.sparqlstore.layout import Layout, unskolem
from kb.terms import Node

RESULTS_JSON = "application/sparql-results+json"


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
        """``timeout``: seconds any one request may take (also with a shared client); ``http``: a
        client (connection pool) to share with other endpoints of the same server; it stays the
        caller's to close."""
        if isinstance(timeout, bool) or not isinstance(timeout, int | float) or not timeout > 0:
            raise KbError(f"the store timeout must be a number of seconds > 0, got {timeout!r}")
        self.spec = spec if isinstance(spec, StoreSpec) else StoreSpec.parse(spec)
        self.timeout = float(timeout)
        self._own_http = http is None
        self._http = http if http is not None else httpx.Client(
            timeout=timeout, limits=httpx.Limits(max_keepalive_connections=16))

    @property
    def layout(self) -> Layout:
        return self.spec.layout

    def close(self) -> None:
        if self._own_http:
            self._http.close()

    def select(self, query: str, deadline: Deadline | None = None, *,
               timeout: float | None = None) -> list[dict[str, Node]]:
        """The rows of a SELECT query, as rdflib terms (unbound variables left out); ``deadline``
        bounds the request and the reading of the answer (``QueryTimeout``), ``timeout`` a request
        without one (default: the endpoint's)."""
        body = json.loads(self._query(query, RESULTS_JSON, deadline=deadline, timeout=timeout)[1])
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

    def update(self, update: str, timeout: float | None = None) -> None:
        """One update request: the store applies all of it or none of it. ``OutcomeUnknown`` when
        it was sent and no answer came within ``timeout`` (default: the endpoint's)."""
        self._send("POST", self.spec.update_url, timeout=timeout, changes=True, content=update.encode(),
                   headers={"content-type": "application/sparql-update"})

    def _query(self, query: str, accept: str, default_graphs: list[str] | None = None,
               deadline: Deadline | None = None, *, timeout: float | None = None) -> tuple[str, bytes]:
        """The answer's content type and body; with a deadline, the request and the reading of the answer stop
        there (``QueryTimeout``; the store itself may go on with the query: SPARQL has no way
        to cancel one)."""
        form: dict[str, str | list[str]] = {"query": query}
        if default_graphs:
            form["default-graph-uri"] = default_graphs
        if deadline is None:
            response = self._send("POST", self.spec.query_url, timeout=timeout, data=form,
                                  headers={"accept": accept})
            return response.headers.get("content-type", accept), response.content
        request = self._http.build_request("POST", self.spec.query_url, data=form, headers={"accept": accept},
                                           timeout=min(deadline.remaining(), self.timeout))
        try:
            response = self._checked(self.spec.query_url, lambda: self._http.send(request, stream=True))
            with closing(response):
                if response.is_error:
                    response.read()
                    raise StoreUnavailable(f"the SPARQL store at {self.spec.query_url} answered "
                                           f"{response.status_code}: {response.text[:300]}")
                chunks = []
                for chunk in response.iter_bytes():
                    deadline.check()
                    chunks.append(chunk)
                return response.headers.get("content-type", accept), b"".join(chunks)
        except httpx.TimeoutException:
            if deadline.remaining() > 0:  # the store's own timeout came first
                raise StoreUnavailable(f"the SPARQL store at {self.spec.query_url} did not answer within "
                                       f"{self.timeout:g} s") from None
            raise QueryTimeout(deadline.seconds) from None
        except httpx.HTTPError as exc:
            raise StoreUnavailable(f"the SPARQL store at {self.spec.query_url} cannot be reached: "
                                   f"{exc}") from exc

    def _checked(self, url: str, send: Callable[[], httpx.Response]) -> httpx.Response:
        if self._http.is_closed:  # httpx would raise a bare RuntimeError
            raise StoreUnavailable(f"the connection to the SPARQL store at {url} was closed")
        return send()

    def _send(self, method: str, url: str, *, timeout: float | None = None, changes: bool = False,
              **kwargs: Any) -> httpx.Response:
        seconds = self.timeout if timeout is None else timeout
        try:
            response = self._checked(url, lambda: self._http.request(method, url, timeout=seconds, **kwargs))
        except _NOT_SENT as exc:
            raise StoreUnavailable(f"the SPARQL store at {url} cannot be reached: {exc}") from exc
        except httpx.TimeoutException as exc:
            raise (OutcomeUnknown if changes else StoreUnavailable)(
                f"the SPARQL store at {url} did not answer within {seconds:g} s") from exc
        except httpx.HTTPError as exc:
            raise (OutcomeUnknown if changes else StoreUnavailable)(
                f"the SPARQL store at {url} failed to answer: {exc}") from exc
        if response.is_error:
            # A 4xx is the store's own refusal of the whole request; a 5xx may come from a proxy
            # that gave up while the store goes on, so an update's fate is then unknown.
            unknown = changes and response.status_code >= 500
            raise (OutcomeUnknown if unknown else StoreUnavailable)(
                f"the SPARQL store at {url} answered {response.status_code}: {response.text[:300]}")
        return response


#: Failures before any byte of the request left: the store cannot have seen it.
_NOT_SENT = (httpx.ConnectError, httpx.ConnectTimeout, httpx.PoolTimeout, httpx.UnsupportedProtocol)


def _node(value: dict[str, str]) -> Node:
    kind = value["type"]
    if kind == "uri":
        return unskolem(value["value"])
    if kind == "bnode":
        return BNode(value["value"])
    datatype = value.get("datatype")
    return Literal(value["value"], lang=value.get("xml:lang"),
                   datatype=URIRef(datatype) if datatype else None)
