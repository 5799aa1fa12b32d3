"""`situated bench grounding`, short: a small world, few rounds. The run checks that the maintained
snapshot equals a full build; figures are not asserted here: they are the benchmark's."""

from __future__ import annotations

import pytest

import bench.grounding
from api.cli import main as cli


def test_a_short_run_has_a_row_per_case_and_the_load_average() -> None:
    out = bench.grounding.run((1500,), rounds=3, baseline_rounds=1, visible_counts=(10, 40))
    rows = [line.split() for line in out.splitlines() if line.strip()[:1].isdigit()]
    assert [row[1] for row in rows] == ["10", "40"]
    assert all(len(row) == 9 and all(float(v.replace(",", "")) >= 0 for v in row) for row in rows)
    assert "load average" in out


def test_bad_rounds_are_refused(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exc:
        cli(["bench", "grounding", "--rounds", "0"])
    assert exc.value.code == 2
    assert "--rounds must be at least 1, not 0" in capsys.readouterr().err


def test_quiet_spells_have_a_row_per_spell_beside_the_turn_after_one_tick() -> None:
    out = bench.grounding.spells_table((1500,), (1,), 1)
    rows = [line.split() for line in out.splitlines() if line.strip()[:1].isdigit()]
    assert [row[1] for row in rows] == ["1"]
    # statements, minutes, median, slowest, cpu, baseline, baseline cpu, behind
    assert all(len(row) == 8 and all(float(v.replace(",", "")) > 0 for v in row[:7]) for row in rows)
    assert all(row[7] in ("0/1", "1/1") for row in rows)  # whether the worker was behind after the spell
    assert "baseline" in out and "cpu" in out and "load average" in out


def test_bad_spell_sizes_are_refused(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exc:
        cli(["bench", "grounding", "--quick", "--rounds", "1", "--spells", "--spell-sizes", "300k"])
    assert exc.value.code == 2
    assert "--spell-sizes takes numbers separated by commas, not '300k'" in capsys.readouterr().err
