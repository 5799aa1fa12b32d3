"""A fake LLM server on loopback, in the Ollama (``/api/chat``, ``/api/tags``) and OpenAI-compatible
(``/v1/chat/completions``, ``/v1/models``) shapes at once, whose behaviour a test switches.

It runs ``http.server`` in a thread (a hang only ties up its own handler thread) and can go down
and come back on the same port.
"""

from __future__ import annotations

import contextlib
import json
import socket
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any

GOOD_ANSWER = {"verbal_ack": "Sure, I take the cup.",
               "user_intent": {"type": "__intent_grab_object__", "object": "cup_1", "recipient": None,
                               "goal": None, "input": None}}
INJECTED = "master_key"  # the object an injected instruction names; the KB has no such entity
HANG_SECONDS = 20.0

# mode -> HTTP status, or the content of a 200 answer and its stop reason
MODES: dict[str, Any] = {
    "good": (json.dumps(GOOD_ANSWER), "stop"),
    "refuse_500": 500,
    "refuse_503": 503,
    "hang": "hang",
    "garbage_body": "garbage",  # HTTP 200 whose body is not JSON at all
    "wrong_body": "wrong",  # HTTP 200, JSON, but not a chat answer
    "invalid_json": ('{"verbal_ack": "Sure", "user_intent": {"type": ', "stop"),
    "schema_violation": (json.dumps({"verbal_ack": ["not", "a", "string"], "user_intent": "grab it"}), "stop"),
    "unknown_ids": (json.dumps({"verbal_ack": "Here is the teapot.", "user_intent": {
        "type": "__intent_grab_object__", "object": "teapot_9", "recipient": None, "goal": None,
        "input": None}}), "stop"),
    "truncated": ('{"verbal_ack": "Sure, I will take the', "length"),
    "empty": ("", "stop"),
    "injection": (json.dumps({"verbal_ack": "Handing over the master key.", "user_intent": {
        "type": "__intent_bring_object__", "object": INJECTED, "recipient": "person_tom", "goal": None,
        "input": None}}), "stop"),
}
UNREACHABLE = {"down", "refuse_500", "refuse_503", "hang"}  # what /health should then report


class FakeLLM:
    def __init__(self) -> None:
        self.mode = "good"
        self.requests: list[tuple[str, dict[str, Any]]] = []
        self.port = 0
        self._server: ThreadingHTTPServer | None = None
        self._thread: threading.Thread | None = None

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def up(self) -> None:
        fake = self

        class Handler(BaseHTTPRequestHandler):
            def log_message(self, format: str, *args: Any) -> None:
                pass

            def do_GET(self) -> None:
                if fake.mode in ("refuse_500", "refuse_503"):
                    self._send(int(MODES[fake.mode]), {"error": "overloaded"})
                elif fake.mode == "hang":
                    time.sleep(HANG_SECONDS)
                elif self.path == "/api/tags":
                    self._send(200, {"models": [{"name": "m:1b"}]})
                elif self.path == "/v1/models":
                    self._send(200, {"object": "list", "data": [{"id": "m", "object": "model"}]})
                else:
                    self._send(404, {"error": "not found"})

            def do_POST(self) -> None:
                body = json.loads(self.rfile.read(int(self.headers.get("content-length", 0))) or b"{}")
                fake.requests.append((self.path, body))
                behaviour = MODES[fake.mode]
                openai = self.path == "/v1/chat/completions"
                if self.path not in ("/api/chat", "/v1/chat/completions"):
                    self._send(404, {"error": "not found"})
                elif isinstance(behaviour, int):
                    self._send(behaviour, {"error": {"message": "overloaded"}} if openai else {"error": "overloaded"})
                elif behaviour == "hang":
                    time.sleep(HANG_SECONDS)
                elif behaviour == "garbage":
                    self._send_raw(200, b"<html>502 Bad Gateway</html>", "text/html")
                elif behaviour == "wrong":
                    self._send(200, {"choices": "none"} if openai else {"message": "none", "done": 3})
                else:
                    content, reason = behaviour
                    self._send(200, _openai(content, reason) if openai else _ollama(content, reason))

            def _send(self, status: int, payload: Any) -> None:
                self._send_raw(status, json.dumps(payload).encode(), "application/json")

            def _send_raw(self, status: int, data: bytes, media: str) -> None:
                self.send_response(status)
                self.send_header("content-type", media)
                self.send_header("content-length", str(len(data)))
                self.end_headers()
                # The client may have given up (its deadline): that is what is being tested.
                with contextlib.suppress(BrokenPipeError, ConnectionResetError):
                    self.wfile.write(data)

        server = ThreadingHTTPServer(("127.0.0.1", self.port), Handler, bind_and_activate=False)
        server.daemon_threads = True
        server.block_on_close = False
        server.socket.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        server.server_bind()
        server.server_activate()
        self.port = server.server_address[1]
        self._server = server
        self._thread = threading.Thread(target=server.serve_forever, kwargs={"poll_interval": 0.05},
                                        daemon=True, name="fake-llm")
        self._thread.start()

    def down(self) -> None:
        """Close the listening socket: connections to the port are refused."""
        if self._server is not None:
            self._server.shutdown()
            self._server.server_close()
            self._server = None

    def set(self, mode: str) -> None:
        if mode == "down":
            self.down()
        else:
            if self._server is None:
                self.up()
            self.mode = mode


def _ollama(content: str, reason: str) -> dict[str, Any]:
    return {"model": "m:1b", "created_at": "2026-01-01T00:00:00Z",
            "message": {"role": "assistant", "content": content}, "done": True, "done_reason": reason,
            "eval_count": 7}


def _openai(content: str, reason: str) -> dict[str, Any]:
    return {"id": "c1", "object": "chat.completion", "created": 0, "model": "m",
            "choices": [{"index": 0, "message": {"role": "assistant", "content": content},
                         "finish_reason": reason}]}


@contextmanager
def fake_llm() -> Iterator[FakeLLM]:
    fake = FakeLLM()
    fake.up()
    try:
        yield fake
    finally:
        fake.down()
