"""A tiny HTTP server on a loopback port that records JSON requests and plays canned replies."""

from __future__ import annotations

import json
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any


@dataclass
class FakeServer:
    url: str
    requests: list[tuple[str, dict[str, Any]]] = field(default_factory=list)
    replies: list[tuple[int, Any]] = field(default_factory=list)
    delay: float = 0.0
    #: The client's (host, port) of each request: one port for several requests is one connection.
    peers: list[tuple[str, int]] = field(default_factory=list)


@contextmanager
def fake_server(keep_alive: bool = False) -> Iterator[FakeServer]:
    """`keep_alive`: HTTP/1.1, connections stay open between requests (else one per request)."""
    state = FakeServer(url="")

    class Handler(BaseHTTPRequestHandler):
        protocol_version = "HTTP/1.1" if keep_alive else "HTTP/1.0"

        def do_POST(self) -> None:
            state.peers.append(self.client_address[:2])
            length = int(self.headers.get("Content-Length", "0"))
            body = json.loads(self.rfile.read(length) or b"{}")
            state.requests.append((self.path, body))
            if state.delay:
                threading.Event().wait(state.delay)
            status, reply = state.replies.pop(0) if state.replies else (500, {"error": "no reply left"})
            data = reply if isinstance(reply, bytes) else json.dumps(reply).encode()
            try:
                self.send_response(status)
                self.send_header("Content-Type", "application/json")
                self.send_header("Content-Length", str(len(data)))
                self.end_headers()
                self.wfile.write(data)
            except (BrokenPipeError, ConnectionResetError):
                pass  # the client gave up (timeout tests)

        def log_message(self, format: str, *args: Any) -> None:
            pass

    server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    server.daemon_threads = True
    server.block_on_close = False
    state.url = f"http://127.0.0.1:{server.server_address[1]}"
    thread = threading.Thread(target=server.serve_forever, kwargs={"poll_interval": 0.02}, daemon=True)
    thread.start()
    try:
        yield state
    finally:
        server.shutdown()
        server.server_close()


def free_port_url() -> str:
    """A loopback URL where nothing listens (the port was bound then released)."""
    import socket

    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        port = sock.getsockname()[1]
    return f"http://127.0.0.1:{port}"
