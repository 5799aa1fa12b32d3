"""Bulk load and memory for `situated bench kb` (issue 18), each measure in a fresh process.

The world is `bench.worlds.QueryWorld` of the given size. Each way into the KB is timed from an
empty process to a loaded KB (the default ontology's closure included, as at a service's start):
``load_data`` of an N-Triples document, ``update`` in batches of 5,000 statements, ``load`` of
the same triples as a Turtle file (up to 200k), and journal recovery of a snapshot of the same
state followed by 10,000 journaled perception ticks. The process's RSS is read after each load
(and its peak). The baseline, in the same run: pyoxigraph loading the same document (no
reasoning), and holding the triples the KB materialised. ``python -m bench.bulk MODE SIZE DIR``
is one child; it prints its figures as JSON.
"""

from __future__ import annotations

import gc
import json
import shutil
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from bench.progress import step
from bench.worlds import QueryWorld

BATCH = 5_000
TICKS = 10_000  # perception ticks journaled after the snapshot that recovery replays


def ticks_for(size: int) -> int:
    """Ticks journaled after the snapshot (fewer for a small world, so a short run stays short)."""
    return min(TICKS, size // 10)
ASSERTED = "asserted.nt"
TURTLE = "asserted.ttl"
TURTLE_UP_TO = 200_000  # rdflib writes the Turtle document: minutes and gigabytes at 1M
MATERIALISED = "materialised.nt"
JOURNAL = "journal"


def memory() -> tuple[int, int]:
    """(RSS, peak RSS) of this process in MB."""
    fields = {}
    for line in Path("/proc/self/status").read_text().splitlines():
        key, _, value = line.partition(":")
        fields[key] = value
    return int(fields["VmRSS"].split()[0]) // 1024, int(fields["VmHWM"].split()[0]) // 1024


def write_document(size: int, directory: Path) -> None:
    """The world's statements as an N-Triples document (what ``load_data`` gets)."""
    from kb.records import nt
    from kb.terms import parse_statement

    lines = {nt(parse_statement(s)) for s in QueryWorld(size).statements()}  # type: ignore[arg-type]
    (directory / ASSERTED).write_text("".join(f"{line} .\n" for line in sorted(lines)), encoding="utf-8")


class _Clock:
    """Wall and CPU seconds of the timed part (the machine is shared: CPU time shows the work)."""

    def __init__(self) -> None:
        self.wall, self.cpu = time.perf_counter(), time.process_time()

    def stop(self) -> tuple[float, float]:
        return time.perf_counter() - self.wall, time.process_time() - self.cpu


def _report(kb: Any, times: tuple[float, float]) -> dict[str, Any]:
    gc.collect()
    rss, peak = memory()
    return {"seconds": times[0], "cpu": times[1], "rss": rss, "peak": peak,
            "asserted": kb.size(inferred=False), "materialised": kb.size()}


def _by_update(size: int, directory: Path) -> dict[str, Any]:
    from kb import KB
    from kb.journal import Journal
    from kb.records import nt

    statements = list(QueryWorld(size).statements())
    gc.collect()
    clock = _Clock()
    kb = KB()
    for at in range(0, len(statements), BATCH):
        kb.update(statements[at : at + BATCH])
    times = clock.stop()
    del statements
    report = _report(kb, times)
    # What the other children load: the triples it materialised, a snapshot of this state and
    # perception ticks journaled after it (a service snapshots every 50,000 records).
    with (directory / MATERIALISED).open("w", encoding="utf-8") as out:
        for triple in kb.writer.models.default.closure:
            out.write(f"{nt(triple)} .\n")
    shutil.rmtree(directory / JOURNAL, ignore_errors=True)  # a journal of an earlier run is not this one's
    journal = Journal(directory / JOURNAL)
    journal.recover(kb)
    journal.snapshot(kb)
    objects = size // 6
    window: list[list[str]] = []
    for tick in range(ticks_for(size)):
        window.append([f"human_{tick % 40} looksAt obj_{(tick * 7919) % objects}",
                       f"obj_{(tick * 104729) % objects} isIn room_{tick % 7}",
                       f"human_{tick % 40} sees obj_{(tick * 15485863) % objects}"])
        kb.apply(add=window[-1], remove=window.pop(0) if len(window) > 3 else [])
    journal.close()
    return report


def _by_load_data(size: int, directory: Path) -> dict[str, Any]:
    from kb import KB

    document = (directory / ASSERTED).read_bytes()
    gc.collect()
    clock = _Clock()
    kb = KB()
    kb.load_data(document, "nt")
    times = clock.stop()
    del document
    return _report(kb, times)


def _by_load(size: int, directory: Path) -> dict[str, Any]:
    from kb import KB

    gc.collect()
    clock = _Clock()
    kb = KB()
    kb.load(directory / TURTLE)
    return _report(kb, clock.stop())


def _by_recovery(size: int, directory: Path) -> dict[str, Any]:
    from kb import KB
    from kb.journal import Journal

    gc.collect()
    clock = _Clock()
    kb = KB()
    Journal(directory / JOURNAL).recover(kb)
    return _report(kb, clock.stop())


def _empty(size: int, directory: Path) -> dict[str, Any]:
    from kb import KB

    kb = KB()
    return _report(kb, (0.0, 0.0))


def _pyoxigraph(name: str) -> Callable[[int, Path], dict[str, Any]]:
    def load(size: int, directory: Path) -> dict[str, Any]:
        from bench.pyoxi import load_seconds

        document = (directory / name).read_bytes()
        gc.collect()
        cpu = time.process_time()
        seconds, count = load_seconds(document)
        cpu = time.process_time() - cpu
        del document
        gc.collect()
        rss, peak = memory()
        return {"seconds": seconds, "cpu": cpu, "rss": rss, "peak": peak, "triples": count}

    return load


CHILDREN: dict[str, Callable[[int, Path], dict[str, Any]]] = {
    "update": _by_update,
    "load_data": _by_load_data,
    "load_turtle": _by_load,
    "recover": _by_recovery,
    "empty": _empty,
    "oxigraph_asserted": _pyoxigraph(ASSERTED),
    "oxigraph_materialised": _pyoxigraph(MATERIALISED),
}


def measure(mode: str, size: int, directory: Path) -> dict[str, Any]:
    """One child's figures (a fresh Python process, so its RSS is the load's alone)."""
    done = subprocess.run([sys.executable, "-m", "bench.bulk", mode, str(size), str(directory)],
                          capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"bench.bulk {mode} {size} failed: {done.stderr[-2000:]}")
    figures: dict[str, Any] = json.loads(done.stdout.splitlines()[-1])
    return figures


Row = tuple[str, str, str, str]


def rows(size: int, directory: Path, with_oxigraph: bool, load_target: str, rss_target: str) -> list[Row]:
    """The bulk-load rows of one world size; ``directory`` is scratch space."""
    step("kb", f"bulk load of {size:,} statements: the N-Triples document")
    write_document(size, directory)
    step("kb", f"bulk load of {size:,}: update in batches of {BATCH:,} (a fresh process)")
    update = measure("update", size, directory)
    step("kb", f"bulk load of {size:,}: load_data of the document")
    loaded = measure("load_data", size, directory)
    turtle = None
    if size <= TURTLE_UP_TO:
        step("kb", f"bulk load of {size:,}: `load` of the same triples as a Turtle file")
        _write_turtle(directory)
        turtle = measure("load_turtle", size, directory)
    step("kb", f"bulk load of {size:,}: journal recovery of a snapshot")
    recovered = measure("recover", size, directory)
    empty = measure("empty", 0, directory)
    if with_oxigraph:
        step("kb", f"bulk load of {size:,}: pyoxigraph, the same document and the materialised triples")
        asserted = measure("oxigraph_asserted", size, directory)
        materialised = measure("oxigraph_materialised", size, directory)
        load_base = (f"pyoxigraph load, same document, no reasoning: {_took(asserted)}; "
                     f"materialised ({materialised['triples']:,}): {_took(materialised)}")
        rss_base = (f"pyoxigraph holding the materialised triples: {materialised['rss']} MB; "
                    f"empty KB process: {empty['rss']} MB")
    else:
        from bench.pyoxi import MISSING

        load_base, rss_base = MISSING, f"{MISSING}; empty KB process: {empty['rss']} MB"
    kb = f"{loaded['asserted']:,} asserted / {loaded['materialised']:,} materialised"
    return [
        (f"bulk load, `load_data` of N-Triples (parse + reasoning), {kb}", _took(loaded), load_base,
         load_target),
        (f"bulk load, `update` in batches of {BATCH:,} statements (same world)", _took(update), "",
         load_target),
        *([("bulk load, `load` of a Turtle file of the same triples (rdflib's parser)", _took(turtle), "",
            load_target)] if turtle is not None else []),
        (f"journal recovery: a snapshot of the same state, then {ticks_for(size):,} perception ticks (+3/−3)",
         _took(recovered), "", load_target),
        (f"RSS after `load_data`, {kb}", f"{loaded['rss']} MB (peak {loaded['peak']} MB)", rss_base,
         rss_target),
    ]


def _write_turtle(directory: Path) -> None:
    from rdflib import Graph

    graph = Graph()
    graph.parse(directory / ASSERTED, format="nt")
    graph.serialize(directory / TURTLE, format="turtle")


def _took(figures: dict[str, Any]) -> str:
    return f"{figures['seconds']:.2f} s (CPU {figures['cpu']:.2f} s)"


def main(argv: list[str]) -> int:
    mode, size, directory = argv[0], int(argv[1]), Path(argv[2])
    print(json.dumps(CHILDREN[mode](size, directory)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
