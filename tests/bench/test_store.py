"""`situated bench store`, short: the smallest world, few rounds, against a real local Oxigraph.
The table has every row and the in-process KB and its RemoteKB replica answer alike; a replica
that answers differently fails the run. Figures are not asserted here: they are the benchmark's."""

from __future__ import annotations

import pytest

import bench.store
from api.cli import main as cli
from bench.oxigraph import oxigraph_command
from kb import KB
from kb.sparqlstore.remote import RemoteKB

SHORT = ["--sizes", "200", "--rounds", "2", "--ticks", "55"]
needs_oxigraph = pytest.mark.skipif(oxigraph_command() is None, reason="the `oxigraph` command is not installed")


@needs_oxigraph
def test_a_short_run_has_every_row_and_equal_answers(capsys: pytest.CaptureFixture[str]) -> None:
    status = cli(["bench", "store", *SHORT])
    out, err = capsys.readouterr()
    assert status == 0, out + err
    rows = [line for line in out.splitlines() if line.startswith("| 200 ")]
    measures = ["perception tick +3/−3", "initial push (attach)", "replica's first query",
                "grounding query (3 patterns)", "one-pattern query", "details human_0", 'lookup "object 12"']
    assert len(rows) == len(measures)
    for row, measure in zip(rows, measures, strict=True):
        assert measure in row
    tick = rows[0].split("|")
    assert "p99" in tick[2] and "(writer + mirror)" in tick[3] and "update" in tick[4]
    for row in rows[3:]:
        assert "1 request" in row or "2 requests" in row
    assert "| consistency: 10 checks, in-process vs RemoteKB" in out and "all equal" in out
    assert "INCONSISTENT" not in err


@needs_oxigraph
def test_a_replica_answering_differently_fails_the_run(monkeypatch: pytest.MonkeyPatch,
                                                        capsys: pytest.CaptureFixture[str]) -> None:
    grounding = bench.store.query_reads()[0]

    def reads() -> list[tuple[str, bench.store.Read]]:
        return [("which side", lambda kb: [type(kb).__name__]), grounding]

    monkeypatch.setattr(bench.store, "query_reads", reads)
    status = bench.store.main(SHORT)
    out, err = capsys.readouterr()
    assert status == 1
    assert "| consistency: 8 checks, in-process vs RemoteKB" in out and "1 DIFFER" in out
    assert f"INCONSISTENT 200: which side: in-process {[KB.__name__]!r} != RemoteKB {[RemoteKB.__name__]!r}" in err


def test_missing_oxigraph_is_a_clear_skip(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(bench.store, "oxigraph_command", lambda: None)
    assert bench.store.main(SHORT) == 2
    assert "skipped, the `oxigraph` command is missing" in capsys.readouterr().err


@pytest.mark.parametrize(("args", "message"), [
    (["--sizes", "1k,ten"], "size 'ten' is not a number"),
    (["--sizes", "50"], "size '50' is too small"),
    (["--rounds", "1"], "'1' must be at least 2"),
    (["--ticks", "51"], "--ticks must be more than 51"),
])
def test_bad_options_say_what_is_wrong(args: list[str], message: str, capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as done:
        bench.store.main(args)
    assert done.value.code == 2
    assert message in capsys.readouterr().err
