"""Load: many concurrent dialogues plus a perception writer, against the service on loopback.

``situated bench load [--seconds 60] [--dialogues 50] [--hz 30]``: the service runs in a child
process (uvicorn on 127.0.0.1, an instant test model, so the service itself is measured); this
process drives it with asyncio + httpx: each dialogue task opens its own dialogue (``POST
/dialogues``) and sends turns back to back, while a perception writer adds a batch of facts
(``POST /kb/revise``) and retracts the batch of a second ago, 30 times a second. Bounded in time
(``--seconds``) and count (``--max-requests``); loopback only. With ``--turns N`` each dialogue sends
exactly N turns and the writer stops once they are done (after two windows of ticks at least), so a
run does the same work however fast the machine is: ``--seconds`` is then only a safety limit.

Reports requests, throughput and p50/p99 latency per route and every error (target: none), then
checks the KB afterwards: the writer's live facts are exactly there, and the materialised closure
equals the closure a fresh KB recomputes from the same asserted triples.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import multiprocessing
import socket
import statistics
import time
from collections.abc import Awaitable, Callable
from dataclasses import dataclass, field
from functools import partial
from typing import Any

import httpx

from bench.progress import step
from dialogue.llm.base import ChatRequest

HOST = "127.0.0.1"
SCENE = [
    "myself rdf:type Robot", "table_1 rdf:type dbr:Table_(furniture)", "cup_1 rdf:type dbr:Cup",
    "cup_1 isOn table_1", "myself sees cup_1", "myself sees table_1",
]
ANSWER = {"verbal_ack": "OK, I take the cup.",
          "user_intent": {"type": "__intent_grab_object__", "object": "cup_1", "recipient": None,
                          "goal": None, "input": None}}
OBJECTS_PER_TICK = 4
WINDOW_TICKS = 30  # the perception batches alive at once: one second of observations at 30 Hz
# A perception node drops a frame while its previous writes are still out, rather than queueing
# them without end: on a loaded machine an unbounded backlog made the client itself the bottleneck
# (thousands of requests waiting in one connection pool, whose scheduling is quadratic).
MAX_TICKS_IN_FLIGHT = 4
TURN = "POST /dialogues/{id}/interactions"
START = "POST /dialogues"
ADD = "POST /kb/revise (add)"
RETRACT = "POST /kb/revise (retract)"


def instant_model(request: ChatRequest) -> str:
    return json.dumps(ANSWER)


def _serve(port: int) -> None:
    """The service, in the child process: the scene, the instant model, uvicorn on loopback."""
    import uvicorn

    from api.app import create_app
    from api.settings import Settings
    from dialogue.llm.testing import FunctionModel
    from kb import KB

    kb = KB()
    kb.update(SCENE)
    model = FunctionModel(instant_model, name="instant")
    app = create_app(Settings(scene=None, port=port), kb=kb, model=model)
    uvicorn.run(app, host=HOST, port=port, log_level="warning")


@dataclass
class Route:
    latencies: list[float] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)

    def percentile(self, q: int) -> float:
        if len(self.latencies) < 2:
            return self.latencies[0] * 1000 if self.latencies else float("nan")
        return statistics.quantiles(self.latencies, n=100)[q - 1] * 1000


@dataclass
class Report:
    seconds: float
    routes: dict[str, Route]
    ticks: int
    late_ticks: int
    hz: float
    dropped_ticks: int = 0
    kb_size: int = 0
    kb_asserted: int = 0
    recomputed_size: int = 0
    closure_equal: bool = False
    live_facts_ok: bool = False
    problems: list[str] = field(default_factory=list)

    @property
    def errors(self) -> int:
        return sum(len(r.errors) for r in self.routes.values())

    @property
    def ok(self) -> bool:
        return self.errors == 0 and self.closure_equal and self.live_facts_ok and not self.problems

    def table(self) -> str:
        lines = [f"{'route':<38} {'requests':>9} {'req/s':>8} {'p50 ms':>8} {'p99 ms':>8} {'errors':>7}"]
        for name, route in self.routes.items():
            lines.append(f"{name:<38} {len(route.latencies):>9} {len(route.latencies) / self.seconds:>8.1f} "
                         f"{route.percentile(50):>8.2f} {route.percentile(99):>8.2f} {len(route.errors):>7}")
        total = sum(len(r.latencies) for r in self.routes.values())
        lines.append(f"{'all':<38} {total:>9} {total / self.seconds:>8.1f} {'':>8} {'':>8} {self.errors:>7}")
        achieved = self.ticks / self.seconds
        lines.append(f"perception writer: {self.hz:g} Hz asked, {achieved:.1f} Hz achieved "
                     f"({self.late_ticks} ticks started late, {self.dropped_ticks} dropped while "
                     f"{MAX_TICKS_IN_FLIGHT} were in flight) over {self.seconds:.1f} s")
        lines.append(f"KB after: {self.kb_size} triples ({self.kb_asserted} asserted); closure recomputed "
                     f"from the asserted triples: {self.recomputed_size} triples, "
                     f"{'identical' if self.closure_equal else 'DIFFERENT'}; the writer's live facts: "
                     f"{'exactly there' if self.live_facts_ok else 'WRONG'}")
        for problem in self.problems:
            lines.append(f"problem: {problem}")
        for name, route in self.routes.items():
            for error in route.errors[:3]:
                lines.append(f"error on {name}: {error}")
        lines.append("result: " + ("OK, no errors" if self.ok else "FAILED"))
        return "\n".join(lines)


class Load:
    def __init__(self, url: str, seconds: float, dialogues: int, hz: float, max_requests: int,
                 turns: int | None = None) -> None:
        self.url, self.seconds, self.dialogues, self.hz = url, seconds, dialogues, hz
        self.max_requests = max_requests
        self.turns = turns
        self.talking = dialogues  # dialogue tasks still sending turns
        self.routes = {name: Route() for name in (START, TURN, ADD, RETRACT)}
        self.sent = 0
        self.ticks = self.late_ticks = self.dropped_ticks = 0
        self.live: dict[int, list[str]] = {}  # tick -> the objects it added, not yet retracted
        self.retracting: set[int] = set()
        self.stop_at = 0.0

    def _more(self) -> bool:
        return time.monotonic() < self.stop_at and self.sent < self.max_requests

    async def _timed(self, name: str, call: Callable[[], Awaitable[httpx.Response]],
                     check: Callable[[httpx.Response], str | None]) -> httpx.Response | None:
        self.sent += 1
        route = self.routes[name]
        start = time.perf_counter()
        try:
            response = await call()
        except httpx.HTTPError as exc:
            route.errors.append(f"{type(exc).__name__}: {exc}")
            return None
        elapsed = time.perf_counter() - start
        problem = check(response)
        if problem:
            route.errors.append(problem)
            return None
        route.latencies.append(elapsed)
        return response

    async def dialogue(self, n: int) -> None:
        # A client (one connection) per dialogue, as each robot or session would have: one shared
        # pool costs the load generator several times more CPU per request than the service.
        async with _client(self.url) as client:
            started = await self._timed(START, lambda: client.post("/dialogues", json={}), _check_started)
            if started is None:
                return
            path = f"/dialogues/{started.json()['dialogue_id']}/interactions"
            turn = {"user_id": f"person_{n}", "input": "please take the cup"}
            sent = 0
            while self._more() and (self.turns is None or sent < self.turns):
                await self._timed(TURN, lambda: client.post(path, json=turn), _check_turn)
                sent += 1
        self.talking -= 1

    def _perceiving(self) -> bool:
        if self.turns is None:
            return self._more()
        # Counted: until the dialogues are done, and long enough for batches to be retracted.
        return self._more() and (self.talking > 0 or self.ticks < 2 * WINDOW_TICKS)

    async def perception(self) -> None:
        """Open loop, like a perception node: a tick every 1/hz s whether or not the previous
        writes are done; each adds its batch, then retracts the batches a window older."""
        period = 1.0 / self.hz
        async with _client(self.url) as client:
            ticks: set[asyncio.Task[None]] = set()
            next_tick = time.monotonic()
            while self._perceiving():
                if len(ticks) < MAX_TICKS_IN_FLIGHT:
                    task = asyncio.create_task(self._tick(client, self.ticks))
                    ticks.add(task)
                    task.add_done_callback(ticks.discard)
                    self.ticks += 1
                else:
                    self.dropped_ticks += 1
                next_tick += period
                delay = next_tick - time.monotonic()
                if delay > 0:
                    await asyncio.sleep(delay)
                else:
                    self.late_ticks += 1
            await asyncio.gather(*ticks)

    async def _tick(self, client: httpx.AsyncClient, tick: int) -> None:
        objects = [f"seen_{tick}_{k}" for k in range(OBJECTS_PER_TICK)]
        added = {"method": "add", "statements": [s for o in objects for s in _facts(o)]}
        if await self._timed(ADD, partial(client.post, "/kb/revise", json=added), _check_revise) is None:
            return
        self.live[tick] = objects
        stale = [t for t in self.live if t <= tick - WINDOW_TICKS and t not in self.retracting]
        self.retracting.update(stale)  # claimed before any await: another tick must not take them too
        for old in stale:
            removed = {"method": "retract", "statements": [s for o in self.live[old] for s in _facts(o)]}
            if await self._timed(RETRACT, partial(client.post, "/kb/revise", json=removed),
                                 _check_revise) is not None:
                del self.live[old]

    async def run(self) -> float:
        start = time.monotonic()
        self.stop_at = start + self.seconds
        await asyncio.gather(self.perception(), *(self.dialogue(n) for n in range(self.dialogues)))
        return time.monotonic() - start


def _client(url: str) -> httpx.AsyncClient:
    # TCP_NODELAY: without it Nagle + delayed ACK add ~40 ms to requests sent in two writes.
    transport = httpx.AsyncHTTPTransport(socket_options=[(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)])
    return httpx.AsyncClient(base_url=url, timeout=60, transport=transport)


def _check_started(response: httpx.Response) -> str | None:
    return None if response.status_code == 201 else f"HTTP {response.status_code}: {response.text[:200]}"


def _facts(obj: str) -> list[str]:
    return [f"{obj} rdf:type dbr:Cup", f"{obj} isOn table_1", f"myself sees {obj}"]


def _check_turn(response: httpx.Response) -> str | None:
    if response.status_code != 200:
        return f"HTTP {response.status_code}: {response.text[:200]}"
    reply = response.json()
    intents = [(i["intent"], i["data"]) for i in reply["intents"]]
    if reply["error_msg"] or intents != [("__intent_grab_object__", {"object": "cup_1"})]:
        return f"unexpected reply: {reply}"
    return None


def _check_revise(response: httpx.Response) -> str | None:
    return None if response.status_code == 200 else f"HTTP {response.status_code}: {response.text[:200]}"


def check_kb(client: httpx.Client, report: Report, live: dict[int, list[str]]) -> None:
    """The writer's live facts are there (and no others), and the closure is the recomputation."""
    from kb import KB

    health = client.get("/health").json()["kb"]
    report.kb_size, report.kb_asserted = health["size"], health["asserted"]
    nt = {"accept": "application/n-triples"}
    asserted = client.get("/kb/export", headers=nt).content
    inferred = client.get("/kb/export", params={"inferred": "true"}, headers=nt).content
    # The export holds the whole asserted state, default ontology included: loading it into an
    # empty KB recomputes everything from scratch (blank nodes get new labels, so they are
    # compared by count only).
    with KB(ontology=False) as fresh:
        fresh.load_data(asserted, "nt")
        report.recomputed_size = fresh.size()
        recomputed = fresh.export("nt", inferred=True)
    report.closure_equal = _lines(inferred) == _lines(recomputed) and report.recomputed_size == report.kb_size
    seen = {r["o"] for r in client.get("/kb/query", params={"pattern": "myself sees ?o"}).json()}
    expected = {o for objects in live.values() for o in objects} | {"cup_1", "table_1"}
    report.live_facts_ok = seen == expected
    if not report.live_facts_ok:
        report.problems.append(f"'myself sees' differs: missing {sorted(expected - seen)[:5]}, "
                               f"extra {sorted(seen - expected)[:5]}")


def _lines(data: bytes) -> set[bytes]:
    return {line.strip() for line in data.splitlines() if line.strip() and b"_:" not in line}


def _free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind((HOST, 0))
        port: int = sock.getsockname()[1]
        return port


def _wait_ready(url: str, process: Any, timeout: float = 60.0) -> None:
    deadline = time.monotonic() + timeout
    with httpx.Client(base_url=url, timeout=2) as client:
        while time.monotonic() < deadline:
            if not process.is_alive():
                raise RuntimeError(f"the service exited with code {process.exitcode}")
            try:
                if client.get("/health").status_code == 200:
                    return
            except httpx.HTTPError:
                time.sleep(0.05)
    raise RuntimeError(f"the service at {url} did not start within {timeout} s")


def run(seconds: float = 60.0, dialogues: int = 50, hz: float = 30.0,
        max_requests: int = 2_000_000, turns: int | None = None) -> Report:
    port = _free_port()
    url = f"http://{HOST}:{port}"
    process = multiprocessing.get_context("spawn").Process(target=_serve, args=(port,), daemon=True)
    step("load", "starting the service in its own process")
    process.start()
    try:
        _wait_ready(url, process)
        step("load", f"{dialogues} dialogues and a {hz:g} Hz perception writer for {seconds:g} s")
        load = Load(url, seconds, dialogues, hz, max_requests, turns)
        elapsed = asyncio.run(load.run())
        step("load", "checking the KB's closure against a recomputation")
        report = Report(elapsed, load.routes, load.ticks, load.late_ticks, hz, load.dropped_ticks)
        with httpx.Client(base_url=url, timeout=60) as client:
            check_kb(client, report, load.live)
        return report
    finally:
        process.terminate()
        process.join(15)
        if process.is_alive():
            process.kill()
            process.join(5)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="situated bench load", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=60.0,
                        help="how long to load the service (default 60)")
    parser.add_argument("--dialogues", type=int, default=50, help="concurrent dialogues (default 50)")
    parser.add_argument("--hz", type=float, default=30.0,
                        help="perception writer ticks per second (default 30)")
    parser.add_argument("--max-requests", type=int, default=2_000_000,
                        help="stop after this many requests in all (default 2000000)")
    parser.add_argument("--turns", type=int, default=None,
                        help="turns per dialogue; the run ends when they are done (--seconds: a limit)")
    args = parser.parse_args(argv)
    if args.seconds <= 0 or args.dialogues < 1 or args.hz <= 0 or args.max_requests < 1:
        parser.error("--seconds, --dialogues, --hz and --max-requests must be positive")
    if args.turns is not None and args.turns < 1:
        parser.error("--turns must be positive")
    report = run(args.seconds, args.dialogues, args.hz, args.max_requests, args.turns)
    print(report.table())
    return 0 if report.ok else 1


if __name__ == "__main__":
    raise SystemExit(main())
