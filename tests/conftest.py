"""Fixtures shared by the test packages: a local Oxigraph SPARQL server for the scale-out tests,
and read replicas (kb.sparqlstore.remote.RemoteKB) of a writer KB mirrored to it."""

from __future__ import annotations

import uuid
from collections.abc import Callable, Iterator
from contextlib import AbstractContextManager, contextmanager
from dataclasses import dataclass
from typing import Any

import httpx
import hypothesis
import pytest

from bench.oxigraph import OxigraphServer, oxigraph_command
from kb import KB
from kb.sparqlstore import text as sparqltext
from kb.sparqlstore.endpoint import SparqlEndpoint
from kb.sparqlstore.mirror import SparqlMirror
from kb.sparqlstore.remote import RemoteKB


def pytest_configure(config: pytest.Config) -> None:
    # No time limit per Hypothesis example (200 ms by default): the suite asserts behaviour, and a
    # busy machine must not fail it. Speed is the benchmarks' (situated bench).
    hypothesis.settings.register_profile("situated", deadline=None)
    hypothesis.settings.load_profile("situated")


@pytest.fixture(scope="session")
def oxigraph() -> Iterator[OxigraphServer]:
    """One in-memory server for the session; tests keep apart by using datasets of their own."""
    if oxigraph_command() is None:
        pytest.skip("the `oxigraph` command is not installed (pip install oxigraph; it is in the test extra)")
    with OxigraphServer(in_memory=True) as server:
        yield server


@pytest.fixture(scope="session")
def oxigraph_http(oxigraph: OxigraphServer) -> Iterator[httpx.Client]:
    """One connection pool for the replicas' endpoints: Oxigraph 0.5 grows slower with every new
    connection that sends it a large update, and each replica starts with one."""
    with httpx.Client(timeout=30.0) as client:
        yield client


@pytest.fixture
def store(oxigraph: OxigraphServer) -> Callable[[], str]:
    """A store URL with a fresh dataset each call: ``sparql+http://...?dataset=t<hex>``."""
    return lambda: oxigraph.store("t" + uuid.uuid4().hex[:12])


@dataclass(frozen=True)
class Replica:
    """A writer KB mirrored to a fresh dataset, and a reader of that dataset writing through it."""

    writer: KB
    reader: RemoteKB
    store: str


@contextmanager
def replica_of(server: OxigraphServer, http: httpx.Client | None = None, **writer_options: Any) -> Iterator[Replica]:
    """``KB(**writer_options)`` + ``SparqlMirror`` on a new dataset + ``RemoteKB`` reading it
    (through the same connection pool, as a service's reader shares it); the dataset is dropped
    afterwards."""
    url = server.store("t" + uuid.uuid4().hex[:12])
    endpoint = SparqlEndpoint(url, http=http)
    writer = KB(**writer_options)
    mirror = SparqlMirror(endpoint)
    mirror.attach(writer)
    reader = RemoteKB(endpoint, writes=writer, poll_interval=0.05)
    try:
        yield Replica(writer, reader, url)
    finally:
        reader.close()
        mirror.detach()
        layout = endpoint.layout
        graphs = [g for name in mirror.stored_models() for g in layout.graphs(name)] + [layout.meta]
        endpoint.update(" ;\n".join(f"DROP SILENT GRAPH {sparqltext.term(g)}" for g in graphs))
        writer.close()
        endpoint.close()


@pytest.fixture(scope="session")
def replicas(oxigraph: OxigraphServer, oxigraph_http: httpx.Client) -> Callable[..., AbstractContextManager[Replica]]:
    """``with replicas(ontology=False) as r: r.reader[...]``: a fresh writer/reader pair per use."""
    return lambda **options: replica_of(oxigraph, oxigraph_http, **options)


@contextmanager
def kb_variant(request: pytest.FixtureRequest, **options: Any) -> Iterator[KB | RemoteKB]:
    """For fixtures parametrised over ``["memory", "sparql"]``: an in-process ``KB(**options)``,
    or a ``RemoteKB`` reading a mirror of one (skipped when Oxigraph is missing)."""
    if request.param == "memory":
        with KB(**options) as kb:
            yield kb
        return
    with request.getfixturevalue("replicas")(**options) as pair:
        yield pair.reader


VARIANTS = ["memory", "sparql"]
