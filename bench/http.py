"""HTTP overhead: ``situated bench http [--seconds 5] [--clients 1,8,32]``.

Requests/s and p50/p99 latency of the dialogue interaction endpoint and of ``/kb/query``, beside a
bare FastAPI echo endpoint, at 1, 8 and 32 concurrent clients, all in the same run against uvicorn on
loopback. The turn is measured twice: answered by the rules (the default backend, which build no
prompt) and by an instant test model (every turn a model turn: its prompt, with the dialogue's
history, its schema and its trace; the service itself is measured, not a model). Each server runs
in a child process of its own, so the load generator does not share its interpreter; each client is
one keep-alive connection sending its requests back to back, each dialogue client in a dialogue of
its own (as many robots or people talking at once). Beside each row, the server's CPU time per
request over the measure (user + system, read off its process): on a shared machine the req/s move
with the load, while the CPU a request costs, against the echo's, says which share of the echo's
throughput the same core's work would allow. The load generator writes HTTP/1.1 itself on
asyncio streams: an HTTP client library costs more CPU per request than the echo it would measure.
Targets (issue 32): each endpoint >= 50% of the echo's requests/s at every client count, its p99
<= 3x the echo's. Loopback only.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import multiprocessing
import os
import socket
import statistics
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

import httpx
from fastapi import FastAPI

from bench.progress import step
from dialogue.llm.base import ChatRequest

HOST = "127.0.0.1"
SCENE = [
    "myself rdf:type Robot", "person_alice rdf:type Human", "person_alice rdfs:label \"Alice\"",
    "table_1 rdf:type dbr:Table_(furniture)", "cup_1 rdf:type dbr:Cup", "cup_1 isOn table_1",
    "book_1 rdf:type dbr:Book", "book_1 isOn table_1", "myself sees cup_1", "myself sees book_1",
    "myself sees table_1", "myself sees person_alice",
]
ANSWER = {"verbal_ack": "OK, I take the cup.",
          "user_intent": {"type": "__intent_grab_object__", "object": "cup_1", "recipient": None,
                          "goal": None, "input": None}}
RATE_TARGET = 0.5
P99_TARGET = 3.0
CLIENTS = (1, 8, 32)
ECHO = "POST /echo (bare FastAPI)"
TURN_RULES = "POST /dialogues/{id}/interactions (rules)"
TURN_MODEL = "POST /dialogues/{id}/interactions (test model)"
NAME = len(TURN_MODEL)  # the endpoint column's width


def echo_app() -> FastAPI:
    app = FastAPI()

    @app.post("/echo")
    async def echo(body: dict[str, Any]) -> dict[str, Any]:
        return body

    return app


def instant_model(request: ChatRequest) -> str:
    return json.dumps(ANSWER)


def no_delay() -> httpx.HTTPTransport:
    """A transport for httpx clients (the ROS bench's, the soak's) that sends each request at once."""
    # httpx writes a POST's headers and body separately: without TCP_NODELAY, Nagle + delayed ACK
    # can add ~40 ms per request, which would measure the kernel, not the service.
    return httpx.HTTPTransport(socket_options=[(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)])


def _serve(which: str, port: int) -> None:
    """One server, in a child process: the echo, or the service with the rules or the instant model."""
    import uvicorn

    if which == "echo":
        uvicorn.run(echo_app(), host=HOST, port=port, log_level="warning")
        return
    from api.app import create_app
    from api.settings import Settings
    from dialogue.llm.testing import FunctionModel
    from kb import KB

    kb = KB()
    kb.update(SCENE)
    model = FunctionModel(instant_model, name="instant") if which == "model" else None
    app = create_app(Settings(scene=None, port=port), kb=kb, model=model)
    uvicorn.run(app, host=HOST, port=port, log_level="warning")


def _free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind((HOST, 0))
        port: int = sock.getsockname()[1]
        return port


@dataclass(frozen=True)
class Server:
    """A server's port, and its process, whose CPU time tells what the requests cost it."""

    port: int
    pid: int

    def cpu(self) -> float | None:
        """Seconds of CPU (user + system) the server has used so far; None without psutil (it comes
        with the test extra: `situated bench` itself does not need it), shown as "-" in the table."""
        try:
            import psutil
        except ImportError:
            return None
        times = psutil.Process(self.pid).cpu_times()
        return float(times.user + times.system)


@contextmanager
def served(which: str) -> Iterator[Server]:
    """A server started in a child process (spawned: nothing of this one shared)."""
    port = _free_port()
    child = multiprocessing.get_context("spawn").Process(target=_serve, args=(which, port), daemon=True)
    child.start()
    try:
        deadline = time.monotonic() + 60
        while True:
            try:
                socket.create_connection((HOST, port), timeout=1).close()
                break
            except OSError:
                if not child.is_alive() or time.monotonic() > deadline:
                    raise RuntimeError(f"the {which} server did not start") from None
                time.sleep(0.05)
        assert child.pid is not None  # started
        yield Server(port, child.pid)
    finally:
        child.terminate()
        child.join(timeout=10)


class Connection:
    """One keep-alive HTTP/1.1 connection that sends JSON POSTs and reads their responses."""

    def __init__(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter, port: int) -> None:
        self.reader, self.writer, self.port = reader, writer, port

    @classmethod
    async def open(cls, port: int) -> Connection:
        reader, writer = await asyncio.open_connection(HOST, port)
        writer.get_extra_info("socket").setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        return cls(reader, writer, port)

    def request(self, path: str, body: dict[str, Any]) -> bytes:
        data = json.dumps(body).encode()
        head = (f"POST {path} HTTP/1.1\r\nHost: {HOST}:{self.port}\r\nContent-Type: application/json\r\n"
                f"Content-Length: {len(data)}\r\n\r\n")
        return head.encode() + data

    async def send(self, request: bytes) -> tuple[int, bytes]:
        """(status, body) of one request."""
        self.writer.write(request)
        status_line = await self.reader.readline()
        length = 0
        while (line := await self.reader.readline()) not in (b"\r\n", b""):
            name, _, value = line.partition(b":")
            if name.strip().lower() == b"content-length":
                length = int(value)
        body = await self.reader.readexactly(length)
        return int(status_line.split()[1]), body

    async def close(self) -> None:
        self.writer.close()
        await self.writer.wait_closed()


@dataclass
class Result:
    name: str
    clients: int
    count: int
    seconds: float
    latencies: list[float]
    cpu: float | None = None  # the server's CPU seconds over the measure

    @property
    def cpu_ms(self) -> float | None:
        """The server's CPU time per request, in ms."""
        return None if self.cpu is None or not self.count else self.cpu / self.count * 1000

    @property
    def rate(self) -> float:
        return self.count / self.seconds

    def percentile(self, q: int) -> float:
        return statistics.quantiles(self.latencies, n=100)[q - 1] * 1000


def _takes_the_cup(reply: dict[str, Any]) -> bool:
    intents = reply.get("intents") or []
    return bool(intents) and intents[0].get("data", {}).get("object") == "cup_1"


async def _load(server: Server, clients: int, seconds: float, path: str, body: dict[str, Any],
                dialogue: bool) -> tuple[list[float], float, float | None]:
    port = server.port
    connections = [await Connection.open(port) for _ in range(clients)]
    requests = []
    for connection in connections:
        target = path
        if dialogue:  # each client in a dialogue of its own
            status, opened = await connection.send(connection.request("/dialogues", {}))
            if status != 201:
                raise RuntimeError(f"POST /dialogues: {status} {opened[:200]!r}")
            target = f"/dialogues/{json.loads(opened)['dialogue_id']}/interactions"
        request = connection.request(target, body)
        status, answer = await connection.send(request)
        if status != 200 or (dialogue and not _takes_the_cup(json.loads(answer))):
            raise RuntimeError(f"POST {target}: not the answer measured: {status} {answer[:300]!r}")
        requests.append(request)
    latencies: list[float] = []
    stop = 0.0

    async def client(connection: Connection, request: bytes, warm: int) -> None:
        for _ in range(warm):  # connections, caches
            await connection.send(request)
        while time.perf_counter() < stop:
            before = time.perf_counter()
            status, answer = await connection.send(request)
            if status != 200:
                raise RuntimeError(f"POST {path}: {status} {answer[:200]!r}")
            latencies.append(time.perf_counter() - before)

    await asyncio.gather(*(client(c, r, 5) for c, r in zip(connections, requests, strict=True)))
    latencies.clear()
    cpu_before = server.cpu()
    start = time.perf_counter()
    stop = start + seconds
    await asyncio.gather(*(client(c, r, 0) for c, r in zip(connections, requests, strict=True)))
    took = time.perf_counter() - start
    cpu_after = server.cpu()
    cpu = None if cpu_before is None or cpu_after is None else cpu_after - cpu_before
    for connection in connections:
        await connection.close()
    return latencies, took, cpu


def measure(name: str, server: Server, clients: int, seconds: float, path: str, body: dict[str, Any],
            dialogue: bool = False) -> Result:
    step("http", f"{name}, {clients} client{'s' if clients > 1 else ''}: {seconds:g} s")
    latencies, took, cpu = asyncio.run(_load(server, clients, seconds, path, body, dialogue))
    return Result(name, clients, len(latencies), took, latencies, cpu)


def _cpu_columns(r: Result, echo: Result) -> str:
    """The server's CPU ms per request, and the echo's against it (the share of the echo's req/s the
    same CPU allows)."""
    if r.cpu_ms is None or echo.cpu_ms is None or not r.cpu_ms:
        return f" {'-':>7} {'-':>8}"
    return f" {r.cpu_ms:>7.2f} {echo.cpu_ms / r.cpu_ms:>8.0%}"


def table(results: list[Result]) -> tuple[str, bool]:
    lines = [f"{'endpoint':<{NAME}} {'clients':>7} {'requests':>8} {'req/s':>8} {'p50 ms':>7} {'p99 ms':>7}"
             f" {'vs echo':>8} {'p99/echo':>8} {'cpu ms':>7} {'by cpu':>8}"]
    ok = True
    echo: Result | None = None
    for r in results:
        if r.name == ECHO:
            echo = r
        assert echo is not None and echo.clients == r.clients  # the echo comes first at each count
        rate, tail = r.rate / echo.rate, r.percentile(99) / echo.percentile(99)
        if r is not echo:
            ok = ok and rate >= RATE_TARGET and tail <= P99_TARGET
        lines.append(f"{r.name:<{NAME}} {r.clients:>7} {r.count:>8} {r.rate:>8.0f} {r.percentile(50):>7.2f}"
                     f" {r.percentile(99):>7.2f} {rate:>7.0%} {tail:>8.2f}{_cpu_columns(r, echo)}")
    legend = ("cpu ms: the server's CPU time per request over the measure; by cpu: the echo's against"
              " it, the share of the echo's req/s that CPU allows whatever the machine's load")
    return "\n".join([*lines, legend]), ok


def run(seconds: float = 5.0, counts: tuple[int, ...] = CLIENTS) -> tuple[str, bool]:
    results: list[Result] = []
    turn = {"user_id": "person_alice", "input": "take the cup"}
    query = {"patterns": ["myself sees ?o"]}
    with served("echo") as echo, served("model") as service, served("rules") as rules:
        for clients in counts:
            results.append(measure(ECHO, echo, clients, seconds, "/echo", query))
            results.append(measure("POST /kb/query", service, clients, seconds, "/kb/query", query))
            results.append(measure(TURN_RULES, rules, clients, seconds, "", turn, dialogue=True))
            results.append(measure(TURN_MODEL, service, clients, seconds, "", turn, dialogue=True))
    report, ok = table(results)
    verdict = "meets" if ok else "MISSES"
    load = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    return (f"{report}\ntargets: >= {RATE_TARGET:.0%} of the echo's req/s and p99 <= {P99_TARGET:g}x the"
            f" echo's at each client count: {verdict} (load average {load})"), ok


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="situated bench http", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=5.0,
                        help="time per endpoint and client count (default 5)")
    parser.add_argument("--clients", default="1,8,32", help="client counts, comma-separated (default 1,8,32)")
    args = parser.parse_args(argv)
    try:
        counts = tuple(int(c) for c in args.clients.split(","))
    except ValueError:
        parser.error(f"--clients takes numbers separated by commas, not {args.clients!r}")
    if args.seconds <= 0 or not counts or min(counts) < 1:
        parser.error("--seconds must be positive and each client count at least 1")
    report, ok = run(args.seconds, counts)
    print(report)
    return 0 if ok else 1


if __name__ == "__main__":
    raise SystemExit(main())
