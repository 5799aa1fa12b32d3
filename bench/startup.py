"""Start-up and memory of the dialogue grounding: ``situated bench startup [--sizes 100000,300000]``.

Each size runs in a fresh process (``python -m bench.startup SIZE`` is one child; it prints its
figures as JSON): the perception world of `bench.grounding` is built (80 things in sight), then a
dialogue engine is made on it and follows it as the service's does, and a question is asked until
its answer is right ("where is the thing 42?": the zone the KB says, named): the time from making
the engine to that first right answer is the start-up, given with the process's CPU time meanwhile
(every thread's: on a shared machine the wall time also waits for a core). The process's RSS is read
after the imports, after the KB is built and once the grounding is built: the KB's own memory and
the grounding's are the differences. Baselines, in the same run: the KB's own memory, for the
grounding's; the issue's figures for the process. Targets (issue 32): start-up <= 3 s at 100k, the
grounding's memory <= the KB's own, a 300k process <= 1.2 GB.
"""

from __future__ import annotations

import argparse
import asyncio
import gc
import json
import os
import subprocess
import sys
import time
from typing import Any

from bench.grounding import SPEAKER, world
from bench.progress import step
from bench.soak import rss_mb

QUESTION = "where is the thing 42?"
#: Seconds the question is asked again for at most (the answer of a turn past its deadline is a
#: polite fallback: asked again, it waits for the grounding).
CAP = 600.0


def child(size: int) -> dict[str, Any]:
    from dialogue.engine import DialogueEngine
    from kb.gcpause import settle

    gc.collect()
    empty = rss_mb()
    kb = world(size, 80)
    gc.collect()
    with_kb = rss_mb()
    zone = kb.find("thing_42 isIn ?z")[0]["z"]
    expected = kb.label(zone)
    start, start_cpu = time.perf_counter(), time.process_time()
    engine = DialogueEngine(kb)
    engine.follow(built=settle)  # as the service's engine (api.services)

    async def first_right() -> str:
        while True:
            said = (await engine.turn(QUESTION, speaker=SPEAKER)).response
            if expected in said or time.perf_counter() - start > CAP:
                return said

    said = asyncio.run(first_right())
    took, cpu = time.perf_counter() - start, time.process_time() - start_cpu  # (every thread's)
    if expected not in said:
        raise RuntimeError(f"no right answer within {CAP:g} s: {said!r} (expected {expected!r})")
    engine.ground()  # everything built: the snapshot and its lexicon
    gc.collect()
    grounded = rss_mb()
    engine.close()
    return {"facts": kb.size(inferred=False), "empty": empty, "kb": with_kb, "all": grounded, "startup": took,
            "cpu": cpu, "answer": said}


def measure(size: int) -> dict[str, Any]:
    step("startup", f"a fresh process: a world of {size:,} statements, then the engine")
    done = subprocess.run([sys.executable, "-m", "bench.startup", "--child", str(size)],
                          capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"bench.startup {size} failed: {done.stderr[-2000:]}")
    figures: dict[str, Any] = json.loads(done.stdout.strip().splitlines()[-1])
    return figures


def run(sizes: tuple[int, ...]) -> str:
    rows = []
    for size in sizes:
        f = measure(size)
        own, grounding = f["kb"] - f["empty"], f["all"] - f["kb"]
        rows.append(f"  {f['facts']:>9,} {f['startup']:>9.2f} {f['cpu']:>9.2f} {own:>9.0f} {grounding:>10.0f}"
                    f" {grounding / own:>7.2f} {f['all']:>9.0f}")
    load = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    return "\n".join([
        "start-up and memory: from making the engine on a built KB to the first right answer (s);"
        " CPU: the process's CPU time meanwhile (s; on a shared machine the wall time waits for a core);"
        " RSS in MB: the KB's own, the grounding's (snapshot and lexicon), the process",
        "  statements  start-up       cpu    KB own  grounding  g / KB   process",
        *rows,
        f"  (targets: start-up <= 3 s at 100k; grounding <= the KB's own (g / KB <= 1); a 300k process"
        f" <= 1,200 MB; load average {load})",
    ])  # fmt: skip


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="situated bench startup", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sizes", default="100000,300000", help="statements, comma-separated")
    parser.add_argument("--child", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child is not None:
        print(json.dumps(child(args.child)))
        return 0
    try:
        sizes = tuple(int(s) for s in args.sizes.split(","))
    except ValueError:
        parser.error(f"--sizes takes numbers separated by commas, not {args.sizes!r}")
    print(run(sizes))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
