"""A real ``situated serve`` in a subprocess on a loopback port, which tests may SIGKILL."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import httpx

from bench.oxigraph import free_port


class ServerProcess:
    """``python -m api.cli serve ARGS --port P``; its output goes to ``log``."""

    def __init__(self, args: list[str], log: Path, env: dict[str, str] | None = None) -> None:
        self.port = free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        self.log = log
        command = [sys.executable, "-m", "api.cli", "serve", *args, "--port", str(self.port)]
        with log.open("ab") as out:
            self.proc = subprocess.Popen(command, stdout=out, stderr=subprocess.STDOUT,
                                         env={**os.environ, **(env or {})})

    def wait_ready(self, timeout: float = 60.0) -> None:
        deadline = time.monotonic() + timeout
        with httpx.Client(base_url=self.url, timeout=2.0) as client:
            while time.monotonic() < deadline:
                if self.proc.poll() is not None:
                    raise RuntimeError(f"the server exited with {self.proc.returncode}; see {self.log}:\n"
                                       + self.log.read_text(errors="replace")[-3000:])
                try:
                    if client.get("/health").status_code == 200:
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
