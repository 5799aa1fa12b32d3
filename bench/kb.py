"""`situated bench kb`: the KB's figures beside baselines measured in the same run.

Baselines: owlrl's full OWL RL closure (what a KB without incremental reasoning must redo after
every change) for the ontology load and the perception tick; rdflib's SPARQL engine on the same
materialised triples for the grounding query. Targets are those of kb-compat §8.8 / issue 2.
"""

from __future__ import annotations

import argparse
import gc
import statistics
import subprocess
import sys
import time
from collections.abc import Callable, Iterable
from importlib.resources import files

import owlrl
from rdflib import Graph
from rdflib.plugins.sparql import prepareQuery

from bench.progress import step
from bench.worlds import QUERY, SPARQL_QUERY, PerceptionWorld, QueryWorld
from kb import KB
from kb.models import Model
from kb.rdfio import DEFAULT_ONTOLOGY, parse_data
from kb.sparql import INIT_NS
from kb.terms import ORO

Row = tuple[str, str, str, str]


def _median_ms(samples: Iterable[float]) -> float:
    return statistics.median(samples) * 1000


def _timed(fn: Callable[[], object], rounds: int) -> list[float]:
    times = []
    for _ in range(rounds):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return times


def _build(statements: Iterable[str]) -> KB:
    kb = KB()
    batch: list[str] = []
    for st in statements:
        batch.append(st)
        if len(batch) == 5000:
            kb.update(batch)
            batch = []
    if batch:
        kb.update(batch)
    return kb


def _rdflib_graph(kb: KB) -> Graph:
    graph = Graph()
    graph.parse(data=kb.export("nt", inferred=True), format="nt")
    return graph


def _owlrl_seconds(kb: KB) -> float:
    graph = Graph()
    graph.parse(data=kb.export("nt"), format="nt")
    start = time.perf_counter()
    owlrl.DeductiveClosure(owlrl.OWLRL_Semantics, axiomatic_triples=False).expand(graph)
    return time.perf_counter() - start


def bench_ontology(rows: list[Row]) -> None:
    step("kb", "ontology load and full closure, then owlrl's closure of it")
    text = (files("ontologies") / DEFAULT_ONTOLOGY).read_text(encoding="utf-8")
    parse = _timed(lambda: parse_data(text, "turtle"), 5)
    triples = parse_data(text, "turtle")
    close = _timed(lambda: Model("default", triples), 5)
    graph = Graph()
    for t in triples:
        graph.add(t)
    start = time.perf_counter()
    owlrl.DeductiveClosure(owlrl.OWLRL_Semantics, axiomatic_triples=False).expand(graph)
    reference = time.perf_counter() - start
    total = statistics.median(parse) + statistics.median(close)
    rows.append((f"ontology load + full closure ({len(triples)} triples)", f"{total * 1000:.0f} ms",
                 f"owlrl closure alone: {reference * 1000:.0f} ms", "≤ 300 ms"))


def bench_ticks(rows: list[Row], objects: int, target: str, with_owlrl: bool) -> None:
    step("kb", f"perception ticks in a world of {objects:,} objects")
    world = PerceptionWorld(objects)
    kb = _build(world.statements())
    ticks = list(world.ticks(400))
    for add, remove in ticks[:50]:  # warm-up
        kb.apply(add, remove)
    gc.collect()
    samples = []
    for add, remove in ticks[50:]:
        start = time.perf_counter()
        kb.apply(add, remove)
        samples.append(time.perf_counter() - start)
    if with_owlrl:
        step("kb", "owlrl's re-closure of the same world")
    baseline = f"owlrl re-closure: {_owlrl_seconds(kb):.2f} s" if with_owlrl else "owlrl: not run (--full)"
    rows.append((f"perception tick +3/−3, {kb.size():,} materialised ({kb.size(inferred=False):,} asserted)",
                 f"{_median_ms(samples):.2f} ms median", baseline, target))
    kb.close()


def bench_query(rows: list[Row], size: int, target: str, sparql_rounds: int) -> None:
    step("kb", f"grounding query in a world of {size:,} asserted, then rdflib SPARQL on it")
    kb = _build(QueryWorld(size).statements())
    for _ in range(20):
        kb.find(QUERY)
    samples = _timed(lambda: kb.find(QUERY), 50)
    answers = len(kb.find(QUERY))
    graph = _rdflib_graph(kb)
    prepared = prepareQuery(SPARQL_QUERY, initNs=INIT_NS, base=ORO)
    baseline_answers = len(list(graph.query(prepared)))
    if baseline_answers != answers:
        raise SystemExit(f"query answers differ: situated {answers}, rdflib {baseline_answers}")
    sparql = _timed(lambda: list(graph.query(prepared)), sparql_rounds)
    rows.append((f"3-pattern grounding query, {kb.size(inferred=False):,} asserted / {kb.size():,} "
                 f"materialised ({answers} answers)",
                 f"{_median_ms(samples):.2f} ms median",
                 f"rdflib SPARQL (prepared): {_median_ms(sparql):.1f} ms", target))
    kb.close()


def bench_rss(rows: list[Row], size: int) -> None:
    step("kb", f"memory of a process holding {size:,} asserted")
    code = (
        "import resource, sys\n"
        "from bench.kb import _build\nfrom bench.worlds import QueryWorld\n"
        f"kb = _build(QueryWorld({size}).statements())\n"
        "rss = [l for l in open('/proc/self/status') if l.startswith('VmRSS')][0].split()[1]\n"
        "print(int(rss) // 1024, kb.size(inferred=False), kb.size())\n"
    )
    empty = (
        "from kb import KB\nkb = KB()\n"
        "print(int([l for l in open('/proc/self/status') if l.startswith('VmRSS')][0].split()[1]) // 1024)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    base = subprocess.run([sys.executable, "-c", empty], capture_output=True, text=True, check=True).stdout
    rss, asserted, closure = (int(x) for x in out.split())
    rows.append((f"RSS with {asserted:,} asserted / {closure:,} materialised", f"{rss} MB",
                 f"empty KB process: {int(base)} MB", "≤ 400 MB"))


def render(rows: list[Row]) -> str:
    return markdown_table(("measure", "situated", "baseline (same run)", "target"), rows)


def markdown_table(header: Row, rows: list[Row]) -> str:
    """Four columns, padded so the table also reads as plain text."""
    widths = [max(len(r[i]) for r in [header, *rows]) for i in range(4)]
    lines = ["| " + " | ".join(h.ljust(w) for h, w in zip(header, widths, strict=True)) + " |",
             "|" + "|".join("-" * (w + 2) for w in widths) + "|"]
    lines += ["| " + " | ".join(c.ljust(w) for c, w in zip(r, widths, strict=True)) + " |" for r in rows]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="situated bench kb", description=__doc__)
    parser.add_argument("--quick", action="store_true", help="small sizes only (seconds, for CI smoke runs)")
    parser.add_argument("--full", action="store_true", help="also run owlrl at ~60k (minutes)")
    args = parser.parse_args(argv)
    rows: list[Row] = []
    bench_ontology(rows)
    bench_ticks(rows, 400, "≤ 1 ms at ~10k", with_owlrl=True)
    if not args.quick:
        bench_ticks(rows, 2900, "≤ 2 ms at ~60k", with_owlrl=args.full)
    bench_query(rows, 10_000, "≤ 0.5 ms at 10k", sparql_rounds=10)
    if not args.quick:
        bench_query(rows, 100_000, "≤ 5 ms at 100k", sparql_rounds=3)
        bench_rss(rows, 100_000)
    print(render(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
