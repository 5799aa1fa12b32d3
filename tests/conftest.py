"""Fixtures shared by the test packages: a local Oxigraph SPARQL server for the scale-out tests."""

from __future__ import annotations

import uuid
from collections.abc import Callable, Iterator

import pytest

from bench.oxigraph import OxigraphServer, oxigraph_command


@pytest.fixture(scope="session")
def oxigraph() -> Iterator[OxigraphServer]:
    """One server for the session; tests keep apart by using datasets of their own."""
    if oxigraph_command() is None:
        pytest.skip("the `oxigraph` command is not installed (pip install oxigraph; it is in the test extra)")
    with OxigraphServer() as server:
        yield server


@pytest.fixture
def store(oxigraph: OxigraphServer) -> Callable[[], str]:
    """A store URL with a fresh dataset each call: ``sparql+http://...?dataset=t<hex>``."""
    return lambda: oxigraph.store("t" + uuid.uuid4().hex[:12])
