"""A real ``situated serve`` in a subprocess on a loopback port, which tests may SIGKILL.

The port comes from a socket closed again at once, and the server binds it only after its
start-up (journal recovery: seconds on a busy machine). Meanwhile any other process may take it
(every test server on the machine binds port 0), so an answer on the port proves nothing: ready
means this process listens on it. A start that found the port taken is retried on another one.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import httpx
import psutil

from bench.oxigraph import free_port

PORT_TAKEN = "address already in use"  # uvicorn's log line when the bind fails (EADDRINUSE)
STARTS = 5  # attempts, each on a new port, when another process took the port first


class ServerProcess:
    """``python -m api.cli serve ARGS --port P`` (or another ``command`` taking serve's options, such
    as ``ros run``); its output goes to ``log``."""

    def __init__(self, args: list[str], log: Path, env: dict[str, str] | None = None,
                 command: tuple[str, ...] = ("serve",), preexec: Callable[[], None] | None = None) -> None:
        """``preexec`` runs in the child before the server starts (limits, signal dispositions)."""
        self.args, self.log, self.env, self.command, self.preexec = args, log, env, command, preexec
        self.starts = 0
        self._spawn()

    def _spawn(self) -> None:
        self.starts += 1
        self.port = free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        self._log_from = self.log.stat().st_size if self.log.exists() else 0
        command = [sys.executable, "-m", "api.cli", *self.command, "--port", str(self.port), *self.args]
        with self.log.open("ab") as out:
            self.proc = subprocess.Popen(command, stdout=out, stderr=subprocess.STDOUT,
                                         env={**os.environ, **(self.env or {})}, preexec_fn=self.preexec)

    def _own_output(self) -> str:
        with self.log.open("rb") as handle:
            handle.seek(self._log_from)
            return handle.read().decode(errors="replace")

    def listens(self) -> bool:
        """True when this process (not another one) listens on the port."""
        try:
            connections = psutil.Process(self.proc.pid).net_connections(kind="tcp")
        except psutil.NoSuchProcess:
            return False
        return any(c.status == psutil.CONN_LISTEN and c.laddr.port == self.port for c in connections)

    def wait_ready(self, timeout: float = 60.0) -> None:
        deadline = time.monotonic() + timeout
        with httpx.Client(timeout=2.0) as client:
            while time.monotonic() < deadline:
                if self.proc.poll() is not None:
                    output = self._own_output()
                    if PORT_TAKEN in output.lower() and self.starts < STARTS:
                        self._spawn()  # another process took the port before this one bound it
                        continue
                    raise RuntimeError(f"the server exited with {self.proc.returncode}; see {self.log}:\n"
                                       + output[-3000:])
                try:
                    if client.get(self.url + "/health").status_code == 200 and self.listens():
                        return
                except httpx.HTTPError:
                    pass
                time.sleep(0.05)
        self.kill()
        raise RuntimeError(f"the server did not become ready in {timeout} s; see {self.log}")

    def kill(self, after: float = 0.0) -> None:
        """SIGKILL (``after`` seconds from now): no shutdown handler, no snapshot, nothing flushed."""
        if after:
            time.sleep(after)
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGKILL)
        self.proc.wait(10)

    def stop(self, timeout: float = 30.0, kill_after: float | None = None) -> int:
        """SIGTERM: a clean stop (uvicorn runs the lifespan's shutdown, which snapshots); with
        ``kill_after``, a SIGKILL that many seconds into it."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
        if kill_after is not None:
            self.kill(after=kill_after)
            return self.proc.returncode
        try:
            return self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            self.kill()
            raise
