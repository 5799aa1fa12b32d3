"""A real ROS 2 graph for the tests: `situated ros run` and a plain rclpy client (the probe), each in
its own process, on a domain of their own, with discovery kept on this machine.

The ROS 2 prefix is built by the test command (`situated ros install --prefix .ros`, or the prefix
named by $SITUATED_ROS_PREFIX, as CI does): without it these tests fail, saying how to build it.
The test process itself never imports rclpy.
"""

from __future__ import annotations

import fcntl
import json
import os
import random
import socket
import subprocess
import sys
import threading
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest

from api.ros.prefix import Prefix, environment
from tests.reliability.server import ServerProcess

ROOT = Path(__file__).resolve().parents[3]
PROBE = Path(__file__).with_name("probe.py")
SCENE = ROOT / "tests" / "api" / "scene.txt"
#: DDS domains usable with the default port mapping on Linux (0 is everyone's default: avoided).
DOMAINS = range(1, 102)
LOCKS = Path("/tmp/situated-ros-domains")


def ros_prefix() -> Prefix:
    root = Path(os.environ.get("SITUATED_ROS_PREFIX", ROOT / ".ros"))
    prefix = Prefix(root.resolve())
    if not prefix.stamp.is_file():
        pytest.fail(f"no ROS 2 prefix at {root}: build it with `.venv/bin/situated ros install --prefix {root}` "
                    "(the README's test command does), or set SITUATED_ROS_PREFIX", pytrace=False)
    return prefix


@pytest.fixture(scope="session")
def prefix() -> Prefix:
    return ros_prefix()


@pytest.fixture
def ros_domain() -> Iterator[int]:
    """A DDS domain no other test (of this run or another on this machine) uses meanwhile."""
    LOCKS.mkdir(exist_ok=True)
    for domain in random.sample(list(DOMAINS), len(DOMAINS)):
        handle = (LOCKS / f"{domain}.lock").open("w")
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            handle.close()
            continue
        try:
            yield domain
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)
            handle.close()
        return
    raise RuntimeError("every DDS domain is taken by other tests")


@pytest.fixture
def ros_env(prefix: Prefix, ros_domain: int, tmp_path: Path) -> dict[str, str]:
    """The environment of every process of the test's graph: the prefix's, localhost-only
    discovery, the test's own domain, logs in the test's folder."""
    return {**os.environ, **environment(prefix), "ROS_DOMAIN_ID": str(ros_domain),
            "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST", "ROS_LOG_DIR": str(tmp_path / "ros_log"),
            "PYTHONUNBUFFERED": "1"}


class Probe:
    """A plain rclpy client process (probe.py), one command per call."""

    def __init__(self, env: dict[str, str], log: Path) -> None:
        self.log = log.open("wb")
        self.proc = subprocess.Popen([sys.executable, str(PROBE)], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=self.log, env=env, text=True)
        first = self._read()
        assert first.get("ready"), first

    def _read(self) -> dict[str, Any]:
        assert self.proc.stdout is not None
        line = self.proc.stdout.readline()
        if not line:
            raise RuntimeError(f"the probe exited ({self.proc.poll()}); see {self.log.name}")
        answer: dict[str, Any] = json.loads(line)
        return answer

    def __call__(self, op: str, **arguments: Any) -> dict[str, Any]:
        assert self.proc.stdin is not None
        self.proc.stdin.write(json.dumps({"op": op, **arguments}) + "\n")
        self.proc.stdin.flush()
        answer = self._read()
        if not answer.pop("ok"):
            raise AssertionError(f"probe {op} failed: {answer['error']}")
        return answer

    def call(self, service: str, type: str, timeout: float = 30.0, **request: Any) -> dict[str, Any]:
        response: dict[str, Any] = self("call", service=service, type=type, request=request,
                                        timeout=timeout)["response"]
        return response

    def messages(self, topic: str, count: int = 1, timeout: float = 30.0) -> list[dict[str, Any]]:
        """The messages received on ``topic`` so far, once there are ``count`` (or ``timeout`` s passed)."""
        received: list[dict[str, Any]] = self("messages", topic=topic, count=count, timeout=timeout)["messages"]
        return received

    def close(self) -> None:
        if self.proc.poll() is None:
            assert self.proc.stdin is not None
            self.proc.stdin.write(json.dumps({"op": "quit"}) + "\n")
            self.proc.stdin.flush()
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait(10)
        self.log.close()


@pytest.fixture
def probe(ros_env: dict[str, str], tmp_path: Path) -> Iterator[Probe]:
    client = Probe(ros_env, tmp_path / "probe.log")
    try:
        yield client
    finally:
        client.close()


class RosNode:
    """`situated ros run` in a subprocess: its HTTP URL, and its process."""

    def __init__(self, server: ServerProcess) -> None:
        self.server = server
        self.url = server.url
        self.http = httpx.Client(base_url=server.url, timeout=60)


@pytest.fixture
def ros_node_factory(ros_env: dict[str, str], tmp_path: Path) -> Iterator[Callable[..., RosNode]]:
    """Start `situated ros run ARGS` (default: the test scene); all are stopped after the test."""
    started: list[RosNode] = []

    def start(*args: str, env: dict[str, str] | None = None) -> RosNode:
        arguments = list(args) if args else ["--scene", str(SCENE)]
        server = ServerProcess(arguments, tmp_path / f"node{len(started)}.log", env={**ros_env, **(env or {})},
                               command=("ros", "run"))
        server.wait_ready(timeout=120)
        node = RosNode(server)
        started.append(node)
        return node

    yield start
    for node in reversed(started):
        node.http.close()
        node.server.stop()


@pytest.fixture
def ros_node(ros_node_factory: Callable[..., RosNode]) -> RosNode:
    return ros_node_factory()


@pytest.fixture
def silent_model() -> Iterator[str]:
    """An --llm spec whose server accepts connections and never answers (a model server hung)."""
    server = socket.create_server(("127.0.0.1", 0))
    held: list[socket.socket] = []
    stop = threading.Event()

    def hold() -> None:
        server.settimeout(0.2)
        while not stop.is_set():
            try:
                held.append(server.accept()[0])
            except TimeoutError:
                continue

    thread = threading.Thread(target=hold, daemon=True)
    thread.start()
    try:
        yield f"hybrid:ollama:silent@http://127.0.0.1:{server.getsockname()[1]}"
    finally:
        stop.set()
        thread.join(5)
        for connection in held:
            connection.close()
        server.close()
