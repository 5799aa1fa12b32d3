"""The service over time: ``situated bench soak [--minutes 60] [--size 100000] [--hz 10]``.

The service runs in this process (uvicorn on loopback, the rules backend, no scene) on a perception
world of ``--size`` statements (`bench.worlds.PerceptionWorld`, 80 things in sight); a perception
client commits a +3/-3 tick ``--hz`` times a second (``POST /kb/apply``: who looks at and holds
what, where things are), and a speaker says one thing a second (``POST
/dialogues/default/interactions``: commands, questions, statements the robot learns). Every minute
prints the turns' latency (median, p99, slowest), the ticks' latency, and the process's RSS. At the
end: RSS growth per minute over the run after its first minute (the warm-up: caches filling), and
whether it levelled off (the last third's growth). Target (issue 32): flat RSS over an hour; the
turn right after a tick as fast at the end as at the start. Loopback only.
"""

from __future__ import annotations

import argparse
import os
import statistics
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

import httpx

from api.app import create_app
from api.server import serve_in_thread
from api.settings import Settings
from bench.grounding import FULL_TURNS, SPEAKER, objects_for, world
from bench.http import no_delay
from bench.progress import step
from bench.worlds import PerceptionWorld

#: RSS growth per minute (MB) under which the process counts as levelled off.
FLAT = 0.25


def rss_mb() -> float:
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    raise RuntimeError("no VmRSS in /proc/self/status")


@dataclass
class Minute:
    turns: list[float] = field(default_factory=list)
    ticks: list[float] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)


def _client() -> httpx.Client:
    return httpx.Client(timeout=30, transport=no_delay())


def _perceive(url: str, ticks: PerceptionWorld, hz: float, stop: threading.Event,
              minutes: list[Minute]) -> None:
    with _client() as client:
        period, due = 1.0 / hz, time.monotonic()
        for add, remove in ticks.ticks(10**9):
            if stop.is_set():
                return
            due += period
            start = time.perf_counter()
            answer = client.post(f"{url}/kb/apply", json={"add": add, "remove": remove})
            elapsed = time.perf_counter() - start
            minute = minutes[-1]
            if answer.is_success:
                minute.ticks.append(elapsed)
            else:
                minute.errors.append(f"tick: {answer.status_code} {answer.text[:200]}")
            time.sleep(max(0.0, due - time.monotonic()))


def _ms(values: list[float], q: float) -> float:
    if not values:
        return float("nan")
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(len(ordered) * q))] * 1000


def run(minutes: int, size: int, hz: float, row_seconds: int = 60) -> tuple[str, bool]:
    """The report and whether RSS levelled off; each row is ``row_seconds`` (a minute but in a
    test's short run)."""
    step("soak", f"building a world of {size:,} statements")
    kb = world(size, 80)
    facts = kb.size(inferred=False)
    ticks = PerceptionWorld(objects_for(size, 80))
    rows: list[str] = []
    rss: list[float] = []
    errors: list[str] = []
    try:
        with serve_in_thread(create_app(Settings(scene=None), kb=kb)) as url, _client() as client:
            step("soak", f"{minutes} min: {hz:g} Hz perception, one turn a second ({facts:,} asserted)")
            record = [Minute()]
            stop = threading.Event()
            perceiver = threading.Thread(target=_perceive, args=(url, ticks, hz, stop, record), daemon=True)
            perceiver.start()
            start = time.monotonic()
            try:
                for n in range(minutes * row_seconds):
                    said = FULL_TURNS[n % len(FULL_TURNS)]
                    before = time.perf_counter()
                    answer = client.post(f"{url}/dialogues/default/interactions",
                                         json={"user_id": SPEAKER, "input": said})
                    took = time.perf_counter() - before
                    minute = record[-1]
                    if answer.is_success:
                        minute.turns.append(took)
                    else:
                        minute.errors.append(f"turn {said!r}: {answer.status_code} {answer.text[:200]}")
                    if (n + 1) % row_seconds == 0:
                        rss.append(rss_mb())
                        record.append(Minute())
                        rows.append(_row(len(rss), minute, rss[-1]))
                        errors += minute.errors
                        step("soak", rows[-1].strip())
                    time.sleep(max(0.0, start + n + 1 - time.monotonic()))
            finally:
                stop.set()
                perceiver.join(timeout=10)
    finally:
        kb.close()
    return _report(rows, rss, errors, size, facts, hz)


def _row(minute: int, record: Minute, rss: float) -> str:
    turns, ticks = record.turns, record.ticks
    return (f"  {minute:>6} {len(turns):>6} {_ms(turns, 0.5):>9.2f} {_ms(turns, 0.99):>9.2f}"
            f" {max(turns, default=float('nan')) * 1000:>9.2f} {len(ticks):>6} {_ms(ticks, 0.5):>9.2f}"
            f" {rss:>8.1f}")


def growth(rss: list[float]) -> float:
    """RSS growth in MB per minute: the least-squares slope over the minutes given."""
    if len(rss) < 2:
        return 0.0
    xs = range(len(rss))
    mean_x, mean_y = statistics.fmean(xs), statistics.fmean(rss)
    covariance = sum((x - mean_x) * (y - mean_y) for x, y in zip(xs, rss, strict=True))
    return covariance / sum((x - mean_x) ** 2 for x in xs)


def _report(rows: list[str], rss: list[float], errors: list[str], size: int, facts: int,
            hz: float) -> tuple[str, bool]:
    after_warmup = rss[1:]
    slope = growth(after_warmup)
    last = growth(after_warmup[-max(2, len(after_warmup) // 3):])
    flat = len(after_warmup) >= 2 and last <= FLAT
    load = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    lines = [
        f"soak: the service on a perception world of {size:,} statements ({facts:,} asserted), {hz:g} Hz"
        " perception, one turn a second (ms; RSS in MB)",
        "  minute  turns    median       p99   slowest  ticks tick:med      RSS",
        *rows,
        f"  RSS growth after the first minute: {slope:+.2f} MB/min; over the last third: {last:+.2f} MB/min"
        f" ({'flat' if flat else 'NOT flat'}: target <= {FLAT} MB/min; load average {load})",
    ]
    if errors:
        lines.append(f"  {len(errors)} errors, the first: {errors[0]}")
    return "\n".join(lines), flat and not errors


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="situated bench soak", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--minutes", type=int, default=60, help="how long (default 60)")
    parser.add_argument("--size", type=int, default=100_000, help="statements in the world (default 100,000)")
    parser.add_argument("--hz", type=float, default=10.0, help="perception ticks a second (default 10)")
    args = parser.parse_args(argv)
    if args.minutes < 1 or args.size < 1000 or not 0 < args.hz <= 100:
        parser.error("--minutes must be at least 1, --size at least 1000, --hz in (0, 100]")
    report, ok = run(args.minutes, args.size, args.hz)
    print(report)
    return 0 if ok else 1


if __name__ == "__main__":
    raise SystemExit(main())
