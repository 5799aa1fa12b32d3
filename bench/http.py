"""HTTP overhead: requests/s and p50/p99 latency of the dialogue interaction endpoint (with an
instant test model) and of ``/kb/query``, beside a bare FastAPI echo endpoint, all measured in the
same run against uvicorn on loopback. Target: each endpoint at >= 50% of the echo's throughput.

One client, sequential keep-alive requests (what a robot's middleware does), a bounded number of
requests and a time cap per endpoint. Loopback only.
"""

from __future__ import annotations

import argparse
import json
import socket
import statistics
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import httpx
from fastapi import FastAPI

from api.app import create_app
from api.server import serve_in_thread
from api.settings import Settings
from bench.progress import step
from dialogue.llm.base import ChatRequest
from dialogue.llm.testing import FunctionModel
from kb import KB

SCENE = [
    "myself rdf:type Robot", "person_alice rdf:type Human", "person_alice rdfs:label \"Alice\"",
    "table_1 rdf:type dbr:Table_(furniture)", "cup_1 rdf:type dbr:Cup", "cup_1 isOn table_1",
    "book_1 rdf:type dbr:Book", "book_1 isOn table_1", "myself sees cup_1", "myself sees book_1",
    "myself sees table_1", "myself sees person_alice",
]
ANSWER = {"verbal_ack": "OK, I take the cup.",
          "user_intent": {"type": "__intent_grab_object__", "object": "cup_1", "recipient": None,
                          "goal": None, "input": None}}
TARGET = 0.5


@dataclass
class Result:
    name: str
    count: int
    seconds: float
    latencies: list[float]

    @property
    def rate(self) -> float:
        return self.count / self.seconds

    def percentile(self, q: int) -> float:
        return statistics.quantiles(self.latencies, n=100)[q - 1] * 1000


def echo_app() -> FastAPI:
    app = FastAPI()

    @app.post("/echo")
    async def echo(body: dict[str, Any]) -> dict[str, Any]:
        return body

    return app


def instant_model(request: ChatRequest) -> str:
    return json.dumps(ANSWER)


def no_delay() -> httpx.HTTPTransport:
    # httpx writes a POST's headers and body separately: without TCP_NODELAY, Nagle + delayed ACK
    # can add ~40 ms per request, which would measure the kernel, not the service.
    return httpx.HTTPTransport(socket_options=[(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)])


def measure(name: str, call: Callable[[], httpx.Response], count: int, seconds: float) -> Result:
    step("http", f"{name}: up to {count} requests or {seconds:g} s")
    for _ in range(min(20, count)):  # warm-up: connections, caches
        call().raise_for_status()
    latencies: list[float] = []
    start = time.perf_counter()
    cap = start + seconds
    while len(latencies) < count and time.perf_counter() < cap:
        before = time.perf_counter()
        call().raise_for_status()
        latencies.append(time.perf_counter() - before)
    return Result(name, len(latencies), time.perf_counter() - start, latencies)


def table(results: list[Result]) -> str:
    echo = results[0].rate
    lines = [f"{'endpoint':<37} {'requests':>8} {'req/s':>8} {'p50 ms':>7} {'p99 ms':>7} {'vs echo':>8}"]
    for r in results:
        lines.append(f"{r.name:<37} {r.count:>8} {r.rate:>8.0f} {r.percentile(50):>7.2f} "
                     f"{r.percentile(99):>7.2f} {r.rate / echo:>7.0%}")
    return "\n".join(lines)


def run(count: int = 1000, seconds: float = 5.0) -> tuple[str, bool]:
    kb = KB()
    kb.update(SCENE)
    model = FunctionModel(instant_model, name="instant")
    results = []
    try:
        with serve_in_thread(echo_app()) as echo_url, \
                serve_in_thread(create_app(Settings(scene=None), kb=kb, model=model)) as url, \
                httpx.Client(timeout=10, transport=no_delay()) as client:
            results.append(measure("POST /echo (bare FastAPI)", lambda: client.post(
                echo_url + "/echo", json={"patterns": ["myself sees ?o"]}), count, seconds))
            results.append(measure("POST /kb/query", lambda: client.post(
                url + "/kb/query", json={"patterns": ["myself sees ?o"]}), count, seconds))
            turn = {"user_id": "person_alice", "input": "take the cup"}
            results.append(measure("POST /dialogues/default/interactions", lambda: client.post(
                url + "/dialogues/default/interactions", json=turn), count, seconds))
            reply = client.post(url + "/dialogues/default/interactions", json=turn).json()
    finally:
        kb.close()
    if not reply["intents"] or reply["intents"][0]["data"].get("object") != "cup_1":
        raise RuntimeError(f"the benchmark turn did not produce the expected intent: {reply}")
    ok = all(r.rate >= TARGET * results[0].rate for r in results[1:])
    verdict = "meets" if ok else "MISSES"
    return f"{table(results)}\ntarget >= {TARGET:.0%} of the echo's req/s: {verdict}", ok


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="situated bench http", description=__doc__)
    parser.add_argument("--count", type=int, default=1000, help="requests per endpoint (default 1000)")
    parser.add_argument("--seconds", type=float, default=5.0, help="time cap per endpoint (default 5)")
    args = parser.parse_args(argv)
    report, ok = run(args.count, args.seconds)
    print(report)
    return 0 if ok else 1


if __name__ == "__main__":
    raise SystemExit(main())
