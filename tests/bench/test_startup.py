"""`situated bench startup`, short: a small world in a fresh process, answered right, its memory
split between the KB and the grounding. Figures are not asserted: they are the benchmark's."""

from __future__ import annotations

import pytest

import bench.startup


def test_a_small_world_starts_and_answers_right_in_a_fresh_process() -> None:
    # The child refuses to report before the answer names the zone the KB says thing 42 is in.
    out = bench.startup.run((1500,))
    rows = [line.split() for line in out.splitlines() if line.strip()[:1].isdigit()]
    assert len(rows) == 1 and len(rows[0]) == 7
    facts, startup, cpu, kb_own, _grounding, _ratio, process = (float(v.replace(",", "")) for v in rows[0])
    assert facts > 1500 and startup > 0 and cpu > 0 and 0 < kb_own < process
    assert "load average" in out


def test_bad_sizes_are_refused(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exc:
        bench.startup.main(["--sizes", "100k"])
    assert exc.value.code == 2
    assert "--sizes takes numbers separated by commas, not '100k'" in capsys.readouterr().err
