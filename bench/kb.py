"""`situated bench kb`: the KB's figures beside baselines measured in the same run.

Baselines: owlrl's full OWL RL closure (what a KB without incremental reasoning must redo after
every change) for the ontology load and the perception tick; rdflib's SPARQL engine on the same
materialised triples for the grounding query; pyoxigraph (a native store, no reasoning; the test
extra) given the same triples, materialised, for the ticks, the queries and the bulk loads
(`bench.bulk`, each in a fresh process so that RSS is its own). Targets are those of kb-compat
§8.8 / issues 2 and 18. `--million` adds the bulk load of 1M statements.
"""

from __future__ import annotations

import argparse
import gc
import os
import statistics
import tempfile
import time
from collections.abc import Callable, Iterable
from importlib.resources import files
from pathlib import Path

import owlrl
from rdflib import Graph
from rdflib.plugins.sparql import prepareQuery

from bench import bulk, pyoxi
from bench.progress import step
from bench.worlds import QUERY, SPARQL_QUERY, PerceptionWorld, QueryWorld
from kb import KB
from kb.models import Model
from kb.rdfio import DEFAULT_ONTOLOGY, parse_data
from kb.sparql import INIT_NS
from kb.terms import ORO, parse_ground

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


def _timed_cpu(fn: Callable[[], object], rounds: int) -> tuple[list[float], list[float]]:
    """Wall and CPU (this thread's) seconds of each round: on a shared machine the CPU time
    leaves out the waits for a core."""
    wall, cpu = [], []
    for _ in range(rounds):
        start, start_cpu = time.perf_counter(), time.thread_time()
        fn()
        cpu.append(time.thread_time() - start_cpu)
        wall.append(time.perf_counter() - start)
    return wall, cpu


def _both_ms(samples: tuple[list[float], list[float]]) -> str:
    return f"{_median_ms(samples[0]):.2f} ms (CPU {_median_ms(samples[1]):.2f})"


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


def bench_ticks(rows: list[Row], objects: int, target: str, with_owlrl: bool, oxigraph: bool) -> None:
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
    baselines = []
    if oxigraph:
        step("kb", "pyoxigraph: the same ticks on the same materialised triples, without reasoning")
        baselines.append(f"pyoxigraph, no reasoning: {_oxigraph_ticks_ms(kb, ticks):.3f} ms")
    if with_owlrl:
        step("kb", "owlrl's re-closure of the same world")
        baselines.append(f"owlrl re-closure: {_owlrl_seconds(kb):.2f} s")
    elif objects > 400:
        baselines.append("owlrl: not run (--full)")
    rows.append((f"perception tick +3/−3, {kb.size():,} materialised ({kb.size(inferred=False):,} asserted)",
                 f"{_median_ms(samples):.2f} ms median", "; ".join(baselines) or pyoxi.MISSING, target))
    kb.close()


def _oxigraph_ticks_ms(kb: KB, ticks: list[tuple[list[str], list[str]]]) -> float:
    store, terms = pyoxi.store_of(kb.writer.models.default.closure)
    parsed = [([parse_ground(s) for s in add], [parse_ground(s) for s in remove]) for add, remove in ticks]
    for add, remove in parsed[:50]:
        pyoxi.apply(store, terms, add, remove)
    samples = []
    for add, remove in parsed[50:]:
        start = time.perf_counter()
        pyoxi.apply(store, terms, add, remove)
        samples.append(time.perf_counter() - start)
    return _median_ms(samples)


def bench_query(rows: list[Row], world: QueryWorld, target: str, sparql_rounds: int, oxigraph: bool,
                what: str = "") -> None:
    step("kb", f"grounding query in a world of {world.size:,} asserted{what}, then rdflib SPARQL on it")
    kb = _build(world.statements())
    for _ in range(20):
        kb.find(QUERY)
    samples = _timed_cpu(lambda: kb.find(QUERY), 50)
    answers = len(kb.find(QUERY))
    graph = _rdflib_graph(kb)
    prepared = prepareQuery(SPARQL_QUERY, initNs=INIT_NS, base=ORO)
    baseline_answers = len(list(graph.query(prepared)))
    if baseline_answers != answers:
        raise SystemExit(f"query answers differ: situated {answers}, rdflib {baseline_answers}")
    sparql = _timed(lambda: list(graph.query(prepared)), sparql_rounds)
    baselines = [f"rdflib SPARQL (prepared): {_median_ms(sparql):.1f} ms"]
    if oxigraph:
        step("kb", "pyoxigraph: the same query on the same materialised triples")
        baselines.insert(0, f"pyoxigraph: {_oxigraph_query_ms(kb, SPARQL_QUERY, ('h', 'o'), answers)}")
    rows.append((f"3-pattern grounding query, {kb.size(inferred=False):,} asserted / {kb.size():,} "
                 f"materialised{what} ({answers} answers)",
                 f"{_both_ms(samples)} median", "; ".join(baselines), target))
    if oxigraph and world.size >= 100_000:
        _one_pattern(rows, kb)
    kb.close()


def _one_pattern(rows: list[Row], kb: KB) -> None:
    step("kb", "a large one-pattern query, and pyoxigraph's")
    pattern, sparql = "?o rdf:type dbr:Cup", "SELECT ?o WHERE { ?o rdf:type dbr:Cup }"
    answers = len(kb.find(pattern))
    samples = _timed_cpu(lambda: kb.find(pattern), 20)
    baseline = _oxigraph_query_ms(kb, sparql, ("o",), answers)
    rows.append((f"one-pattern query `{pattern}` ({answers:,} rows, same world)",
                 f"{_both_ms(samples)} median", f"pyoxigraph: {baseline}", ""))


def _oxigraph_query_ms(kb: KB, sparql: str, names: tuple[str, ...], answers: int) -> str:
    store, _terms = pyoxi.store_of(kb.writer.models.default.closure)
    found = len(pyoxi.select(store, sparql, names))
    if found != answers:
        raise SystemExit(f"query answers differ: situated {answers}, pyoxigraph {found}")
    for _ in range(5):
        pyoxi.select(store, sparql, names)
    return _both_ms(_timed_cpu(lambda: pyoxi.select(store, sparql, names), 30))


def bench_bulk(rows: list[Row], size: int, oxigraph: bool, load_target: str, rss_target: str) -> None:
    with tempfile.TemporaryDirectory(prefix="situated-bulk-") as scratch:
        rows.extend(bulk.rows(size, Path(scratch), oxigraph, load_target, rss_target))


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
    parser.add_argument("--million", action="store_true", help="also bulk-load 1M statements (minutes)")
    args = parser.parse_args(argv)
    oxigraph = pyoxi.warn_if_missing()
    rows: list[Row] = []
    bench_ontology(rows)
    bench_ticks(rows, 400, "≤ 1 ms at ~10k", with_owlrl=True, oxigraph=oxigraph)
    if not args.quick:
        bench_ticks(rows, 2900, "≤ 2 ms at ~60k", with_owlrl=args.full, oxigraph=oxigraph)
        bench_ticks(rows, 30_000, "≤ 0.4 ms at ~100k", with_owlrl=False, oxigraph=oxigraph)
    bench_query(rows, QueryWorld(1_000), "≤ pyoxigraph", sparql_rounds=10, oxigraph=oxigraph)
    bench_query(rows, QueryWorld(10_000), "≤ 0.5 ms at 10k", sparql_rounds=10, oxigraph=oxigraph)
    bench_query(rows, QueryWorld(10_000, cups=0.09, humans=40, sightings=25), "≤ 0.7 ms",
                sparql_rounds=10, oxigraph=oxigraph, what=", 9 % cups, 40 × 25 sightings")
    if not args.quick:
        bench_query(rows, QueryWorld(100_000), "≤ 5 ms at 100k", sparql_rounds=3, oxigraph=oxigraph)
        bench_bulk(rows, 100_000, oxigraph, "≤ 3 s", "≤ 250 MB")
    if args.million:
        bench_bulk(rows, 1_000_000, oxigraph, "≤ 30 s", "≤ 2 GB")
    print(render(rows))
    print(f"(load average {', '.join(f'{x:.2f}' for x in os.getloadavg())} on {os.cpu_count()} cores)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
