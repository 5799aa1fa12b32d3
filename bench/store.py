"""`situated bench store`: the in-process KB beside the same KB kept in a local Oxigraph (issue 9).

One run starts ``oxigraph serve`` (bench.oxigraph) and, for each size, measures side by side:
the perception tick on an in-process KB alone and on a writer whose every commit is mirrored to
the store (kb.sparqlstore.mirror: the tick includes its one update request); the grounding query, a
one-pattern query, ``details`` and ``lookup`` on the in-process KB and on a read replica
(kb.sparqlstore.remote.RemoteKB) answering by SPARQL requests; the initial push (attach) and the replica's
first query on a new connection. Every read compared is also checked for equal answers between
the two; any difference fails the run (exit 1), after the table.
"""

from __future__ import annotations

import argparse
import gc
import statistics
import subprocess
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import partial
from typing import Any

from bench.kb import _build, _median_ms, markdown_table
from bench.oxigraph import OxigraphServer, OxigraphUnavailable, oxigraph_command
from bench.progress import step
from bench.worlds import QUERY, PerceptionWorld, QueryWorld
from kb import KB
from kb.deadline import Deadline
from kb.sparqlstore.endpoint import SparqlEndpoint
from kb.sparqlstore.mirror import SparqlMirror
from kb.sparqlstore.remote import RemoteKB
from kb.terms import Node

Row = tuple[str, str, str, str]
Read = Callable[[KB | RemoteKB], Any]
WARM_UP = 50  # ticks, as bench/kb.py's tick
MIN_SIZE = 200


class CountingEndpoint(SparqlEndpoint):
    """A SPARQL endpoint that counts its requests and keeps the size of every update it sends."""

    def __init__(self, spec: str) -> None:
        super().__init__(spec)
        self.requests = 0
        self.update_bytes: list[int] = []

    def select(self, query: str, deadline: Deadline | None = None, *,
               timeout: float | None = None) -> list[dict[str, Node]]:
        self.requests += 1
        return super().select(query, deadline, timeout=timeout)

    def ask(self, query: str, deadline: Deadline | None = None) -> bool:
        self.requests += 1
        return super().ask(query, deadline)

    def raw(self, query: str, accept: str, default_graphs: list[str],
            deadline: Deadline | None = None) -> tuple[str, bytes]:
        self.requests += 1
        return super().raw(query, accept, default_graphs, deadline)

    def update(self, update: str, timeout: float | None = None) -> None:
        self.requests += 1
        self.update_bytes.append(len(update.encode()))
        super().update(update, timeout)


@dataclass
class Checks:
    """Reads answered by both sides (and the mirror's one-update-per-commit promise); a
    difference is a failure of the replica or the mirror, not noise."""

    compared: int = 0
    failures: list[str] = field(default_factory=list)

    def same(self, what: str, local: object, remote: object) -> None:
        self.compared += 1
        if local != remote:
            self.failures.append(f"{what}: in-process {_clip(local)} != RemoteKB {_clip(remote)}")

    def expect(self, what: str, ok: bool) -> None:
        self.compared += 1
        if not ok:
            self.failures.append(what)


def _clip(value: object, limit: int = 300) -> str:
    text = repr(value)
    return text if len(text) <= limit else text[:limit] + "..."


def _seconds(fn: Callable[[], object]) -> float:
    start = time.perf_counter()
    fn()
    return time.perf_counter() - start


def _samples(fn: Callable[[], object], rounds: int) -> list[float]:
    gc.collect()
    return [_seconds(fn) for _ in range(rounds)]


def _percentile_ms(samples: Sequence[float], q: int) -> float:
    return statistics.quantiles(samples, n=100)[q - 1] * 1000


def _figures(samples: Sequence[float], p99: bool = False) -> str:
    text = f"{_median_ms(samples):.2f} ms median, p90 {_percentile_ms(samples, 90):.2f}"
    return text + (f", p99 {_percentile_ms(samples, 99):.2f}" if p99 else "")


def _ratio(local: Sequence[float], remote: Sequence[float]) -> str:
    return f"{statistics.median(remote) / statistics.median(local):.0f}× in-process"


def _kilobytes(sizes: Sequence[int]) -> str:
    return f"{statistics.median(sizes) / 1000:.1f} kB" if sizes else "none"


def _requests(count: int) -> str:
    return f"{count} request{'s' if count != 1 else ''}"


def _label(size: int) -> str:
    return f"{size // 1000}k" if size % 1000 == 0 else str(size)


def _shape(kb: KB) -> str:
    return f"{kb.size(inferred=False):,} asserted incl. ontology / {kb.size():,} materialised"


def perception_world(size: int) -> PerceptionWorld:
    """The perception world with about ``size`` statements (281 fixed ones + 3.3 per object)."""
    return PerceptionWorld(max(20, round((size - 281) / 3.3)))


def _tick_samples(kb: KB, plan: Sequence[tuple[list[str], list[str]]]) -> list[float]:
    """Seconds per ``kb.apply`` of each tick; the first WARM_UP are the caller's to drop."""
    gc.collect()
    samples = []
    for add, remove in plan:
        start = time.perf_counter()
        kb.apply(add, remove)
        samples.append(time.perf_counter() - start)
    return samples


def bench_ticks(rows: list[Row], checks: Checks, server: OxigraphServer, size: int, ticks: int) -> None:
    name = _label(size)
    step("store", f"perception ticks, world of {size:,} statements, in-process and mirrored")
    world = perception_world(size)
    plan = list(world.ticks(ticks))
    local = _build(world.statements())
    local_samples = _tick_samples(local, plan)[WARM_UP:]
    writer = _build(world.statements())
    endpoint = CountingEndpoint(server.store(f"ticks{size}"))
    mirror = SparqlMirror(endpoint)
    mirror.attach(writer)
    pushed = len(endpoint.update_bytes)
    mirrored = _tick_samples(writer, plan)[WARM_UP:]
    updates = endpoint.update_bytes[pushed:]
    checks.expect(f"{name}: one update request per mirrored tick ({len(updates)} for {len(plan)} ticks)",
                  len(updates) == len(plan))
    rows.append((f"{name} perception tick +3/−3 ({_shape(writer)})", _figures(local_samples, p99=True),
                 _figures(mirrored, p99=True) + " (writer + mirror)",
                 f"{_ratio(local_samples, mirrored)}; update {_kilobytes(updates)} median"))
    with RemoteKB(server.store(f"ticks{size}")) as reader:
        for pattern in ("?p looksAt ?t", "?p holds ?t", "?t isIn zone_3"):
            checks.same(f"{name} after ticks: find {pattern!r}", writer.find(pattern), reader.find(pattern))
        checks.same(f"{name} after ticks: size", writer.size(), reader.size())
        checks.same(f"{name} after ticks: details person_0", writer.details("person_0"),
                    reader.details("person_0"))
    mirror.detach()
    endpoint.close()
    local.close()
    writer.close()


def query_reads() -> list[tuple[str, Read]]:
    """(what, read): the grounding query, a one-pattern query, details of a human, a lookup."""
    return [
        ("grounding query (3 patterns)", lambda kb: kb.find(QUERY)),
        ("one-pattern query ?o isIn room_1", lambda kb: kb.find("?o isIn room_1")),
        ("details human_0", lambda kb: kb.details("human_0")),
        ('lookup "object 12"', lambda kb: kb.lookup("object 12")),
    ]


def bench_queries(rows: list[Row], checks: Checks, server: OxigraphServer, size: int, rounds: int) -> None:
    step("store", f"reads, world of {size:,} statements, in-process and from the store")
    kb = _build(QueryWorld(size).statements())
    store = server.store(f"query{size}")
    endpoint = CountingEndpoint(store)
    mirror = SparqlMirror(endpoint)
    push = _seconds(lambda: mirror.attach(kb))
    rows.append((f"{_label(size)} initial push (attach), {_shape(kb)}", "—", f"{push * 1000:.0f} ms",
                 f"{len(endpoint.update_bytes)} update, {endpoint.update_bytes[-1] / 1e6:.1f} MB"))
    # The replica has its own connection, as a reader process would: its first query opens it.
    reader_endpoint = CountingEndpoint(store)
    reader = RemoteKB(reader_endpoint)
    first = _seconds(lambda: reader.find(QUERY))
    rows.append((f"{_label(size)} replica's first query (new connection)", "—", f"{first * 1000:.2f} ms",
                 _requests(reader_endpoint.requests)))
    for what, read in query_reads():
        reader_endpoint.requests = 0
        answer = read(reader)
        requests = reader_endpoint.requests
        checks.same(f"{_label(size)}: {what}", read(kb), answer)
        for _ in range(5):
            read(kb)
            read(reader)
        local = _samples(partial(read, kb), rounds)
        remote = _samples(partial(read, reader), rounds)
        count = f"{len(answer)} rows" if isinstance(answer, list) else f"{len(answer)} keys"
        rows.append((f"{_label(size)} {what} → {count}", _figures(local), _figures(remote),
                     f"{_ratio(local, remote)}; {_requests(requests)}"))
    reader.close()
    reader_endpoint.close()
    mirror.detach()
    endpoint.close()
    kb.close()


def render(rows: list[Row]) -> str:
    return markdown_table(("measure", "in-process KB", "Oxigraph (mirror / RemoteKB)", "notes"), rows)


def _size(text: str) -> int:
    """``1000`` or ``1k``: a world size in statements."""
    raw = text.strip().lower()
    try:
        value = int(raw[:-1]) * 1000 if raw.endswith("k") else int(raw)
    except ValueError:
        raise argparse.ArgumentTypeError(f"size {text!r} is not a number such as 1000 or 10k") from None
    if value < MIN_SIZE:
        raise argparse.ArgumentTypeError(f"size {text!r} is too small: a world needs {MIN_SIZE}+ statements")
    return value


def _sizes(text: str) -> list[int]:
    return [_size(part) for part in text.split(",")]


def _count(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if value < 2:  # a p90 needs two samples
        raise argparse.ArgumentTypeError(f"{text!r} must be at least 2")
    return value


def _version(command: str) -> str:
    done = subprocess.run([command, "--version"], capture_output=True, text=True, check=False)
    return done.stdout.strip() or "oxigraph (unknown version)"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="situated bench store", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sizes", type=_sizes, default=[1000, 10_000],
                        help="world sizes in statements, comma-separated (default: 1k,10k)")
    parser.add_argument("--rounds", type=_count, default=50, help="timed calls per read (default: 50)")
    parser.add_argument("--ticks", type=_count, default=400,
                        help=f"perception ticks per side, the first {WARM_UP} not counted (default: 400)")
    parser.add_argument("--in-memory", action="store_true",
                        help="run Oxigraph with in-memory storage instead of on disk (RocksDB)")
    args = parser.parse_args(argv)
    if args.ticks <= WARM_UP + 1:
        parser.error(f"--ticks must be more than {WARM_UP + 1}: the first {WARM_UP} are warm-up")
    command = oxigraph_command()
    if command is None:
        print("situated bench store: skipped, the `oxigraph` command is missing "
              "(pip install oxigraph; it is in the test extra)", file=sys.stderr)
        return 2
    rows: list[Row] = []
    checks = Checks()
    try:
        with OxigraphServer(in_memory=args.in_memory) as server:
            storage = "in memory" if args.in_memory else "on disk"
            print(f"{_version(command)} on {server.url}, {storage}; {args.rounds} rounds per read, "
                  f"{args.ticks - WARM_UP} timed ticks", flush=True)
            for size in args.sizes:
                bench_ticks(rows, checks, server, size, args.ticks)
                bench_queries(rows, checks, server, size, args.rounds)
    except OxigraphUnavailable as exc:
        print(f"situated bench store: skipped, {exc}", file=sys.stderr)
        return 2
    verdict = "all equal" if not checks.failures else f"{len(checks.failures)} DIFFER"
    rows.append((f"consistency: {checks.compared} checks, in-process vs RemoteKB", "", "", verdict))
    print(render(rows))
    for failure in checks.failures:
        print(f"situated bench store: INCONSISTENT {failure}", file=sys.stderr)
    return 1 if checks.failures else 0


if __name__ == "__main__":
    raise SystemExit(main())
