"""`situated bench kb`, short: its bulk-load rows in a small world (each load in a fresh process,
beside pyoxigraph's), and a clear notice when pyoxigraph is missing. Figures are not asserted here:
they are the benchmark's."""

from __future__ import annotations

from pathlib import Path

import pytest

import bench.kb
from bench import bulk, pyoxi
from bench.worlds import QueryWorld

needs_pyoxigraph = pytest.mark.skipif(pyoxi.module() is None, reason="pyoxigraph is not installed")


@needs_pyoxigraph
def test_bulk_rows_load_the_same_world_every_way(tmp_path: Path) -> None:
    rows = bulk.rows(3_000, tmp_path, True, "≤ 3 s", "≤ 250 MB")
    assert [row[0].split(",")[0] for row in rows] == [
        "bulk load", "bulk load", "bulk load", "journal recovery: a snapshot of the same state",
        "RSS after `load_data`"]
    assert all(" s (CPU " in row[1] for row in rows[:4]) and rows[4][1].endswith(" MB)")
    assert "pyoxigraph load, same document, no reasoning" in rows[0][2]
    assert "pyoxigraph holding the materialised triples" in rows[4][2]
    loaded = bulk.measure("load_data", 3_000, tmp_path)
    updated = bulk.measure("update", 3_000, tmp_path)
    assert loaded["asserted"] == updated["asserted"] and loaded["materialised"] == updated["materialised"]


@needs_pyoxigraph
def test_the_pyoxigraph_column_answers_the_same_query(capsys: pytest.CaptureFixture[str]) -> None:
    rows: list[bench.kb.Row] = []
    bench.kb.bench_query(rows, QueryWorld(2_000, cups=0.09, humans=10, sightings=5), "", 1, oxigraph=True)
    assert "pyoxigraph: " in rows[0][2] and "rdflib SPARQL" in rows[0][2]


def test_without_pyoxigraph_the_column_says_so(monkeypatch: pytest.MonkeyPatch,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(pyoxi, "module", lambda: None)
    assert pyoxi.warn_if_missing() is False
    assert "pyoxigraph is not installed" in capsys.readouterr().err
    rows: list[bench.kb.Row] = []
    bench.kb.bench_ticks(rows, 60, "", with_owlrl=False, oxigraph=False)
    assert rows[0][2] == pyoxi.MISSING
