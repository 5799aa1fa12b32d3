"""A local Oxigraph SPARQL server in a subprocess, for the scale-out tests and benchmarks.

``oxigraph serve`` comes with the ``oxigraph`` package (the test extra). The server listens on a
free loopback port and keeps its data in a directory of its own.
"""

from __future__ import annotations

import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from types import TracebackType

import httpx


class OxigraphUnavailable(RuntimeError):
    """The ``oxigraph`` command is not installed or the server did not start."""


def oxigraph_command() -> str | None:
    """The ``oxigraph`` executable beside this Python, or on the PATH."""
    beside = Path(sys.executable).with_name("oxigraph")
    return str(beside) if beside.exists() else shutil.which("oxigraph")


def free_port() -> int:
    """A loopback port nothing listens on now (the tests' servers use it too)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind(("127.0.0.1", 0))
        port: int = sock.getsockname()[1]
        return port


class OxigraphServer:
    """``with OxigraphServer() as server: server.store("ds1")`` -> ``sparql+http://...?dataset=ds1``.

    ``in_memory``: keep the data in memory instead of on disk (RocksDB). Tests use it: it is several
    times faster, and Oxigraph 0.5's on-disk store answers large updates sent on new connections
    more slowly with every such connection (keep-alive connections are not affected).
    """

    def __init__(self, location: Path | None = None, *, in_memory: bool = False) -> None:
        self.in_memory = in_memory
        self._own_dir = location is None
        self.location = location if location is not None else Path(tempfile.mkdtemp(prefix="oxigraph-"))
        self.port = free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        self._proc: subprocess.Popen[bytes] | None = None

    def store(self, dataset: str = "situated") -> str:
        return f"sparql+{self.url}?dataset={dataset}"

    def start(self, timeout: float = 20.0) -> OxigraphServer:
        command = oxigraph_command()
        if command is None:
            raise OxigraphUnavailable("the `oxigraph` command is missing: pip install oxigraph")
        self.location.mkdir(parents=True, exist_ok=True)
        log = self.location / "server.log"
        with log.open("ab") as out:
            self._proc = subprocess.Popen(
                [command, "serve", "--location", str(self.location / "db"),
                 "--bind", f"127.0.0.1:{self.port}"],
                stdout=out, stderr=subprocess.STDOUT)
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if self._proc.poll() is not None:
                raise OxigraphUnavailable(
                    f"oxigraph exited with {self._proc.returncode}: {log.read_text()[-2000:]}")
            try:
                httpx.post(self.url + "/query", data={"query": "ASK {}"}, timeout=1.0).raise_for_status()
                return self
            except httpx.HTTPError:
                time.sleep(0.05)
        self.stop()
        raise OxigraphUnavailable(f"oxigraph did not answer within {timeout} s on {self.url}")

    def pause(self) -> None:
        """SIGSTOP: the server stalls (connections are still accepted by the kernel, nothing is
        answered) until ``resume``; how the tests simulate a store that hangs."""
        self._signal(signal.SIGSTOP)
        assert self._proc is not None
        # Stopping every thread of the process is asynchronous: a request sent right away could
        # still be served. On Linux, wait until /proc shows every thread stopped.
        tasks = Path(f"/proc/{self._proc.pid}/task")
        deadline = time.monotonic() + 5.0
        while tasks.is_dir() and time.monotonic() < deadline and not all(
                _stopped(task / "stat") for task in tasks.iterdir()):
            time.sleep(0.01)

    def resume(self) -> None:
        self._signal(signal.SIGCONT)

    def _signal(self, signum: int) -> None:
        if self._proc is None or self._proc.poll() is not None:
            raise OxigraphUnavailable("the oxigraph server is not running")
        self._proc.send_signal(signum)

    def stop(self) -> None:
        if self._proc is not None and self._proc.poll() is None:
            self._proc.send_signal(signal.SIGCONT)  # a paused server cannot act on SIGTERM
            self._proc.terminate()
            try:
                self._proc.wait(10)
            except subprocess.TimeoutExpired:
                self._proc.kill()
                self._proc.wait(10)
        self._proc = None
        if self._own_dir:
            shutil.rmtree(self.location, ignore_errors=True)

    def __enter__(self) -> OxigraphServer:
        return self.start()

    def __exit__(self, kind: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        self.stop()


def _stopped(stat: Path) -> bool:
    """Whether a /proc/PID/task/TID/stat says the thread is stopped (state T), or is gone."""
    try:
        return stat.read_text().rsplit(")", 1)[1].split()[0] in ("T", "t")
    except (OSError, IndexError):
        return True
