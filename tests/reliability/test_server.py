"""The harness that runs a real ``situated serve``: ready means *this* process answers."""

from __future__ import annotations

from pathlib import Path

import httpx
import psutil
import pytest
from fastapi import FastAPI

import tests.reliability.server as harness
from api.server import serve_in_thread
from tests.reliability.server import ServerProcess


def _another_service() -> FastAPI:
    app = FastAPI()

    @app.get("/health")
    def health() -> dict[str, str]:
        return {"status": "ok", "who": "another service"}

    return app


def test_a_port_taken_before_the_server_binds_is_not_mistaken_for_it(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The port comes from a socket that is closed again, and the server binds it only after its
    start-up (recovery: seconds on a busy machine). Another process that takes the port meanwhile
    (any test server on the machine binding port 0) answered ``/health`` in the server's stead, and
    the crash test then read another KB and reported every acknowledged fact lost."""
    with serve_in_thread(_another_service()) as other:
        taken = httpx.URL(other).port
        ports = iter([taken])
        real_free_port = harness.free_port
        monkeypatch.setattr(harness, "free_port", lambda: next(ports, None) or real_free_port())
        server = ServerProcess(["--scene", "none"], tmp_path / "server.log")
        try:
            server.wait_ready()
            assert server.port != taken
            listening = {c.laddr.port for c in psutil.Process(server.proc.pid).net_connections("tcp")
                         if c.status == psutil.CONN_LISTEN}
            assert server.port in listening
            assert "who" not in httpx.get(server.url + "/health").json()
        finally:
            server.stop()
