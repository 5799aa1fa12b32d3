"""`situated bench soak`, short: the service under perception and turns, a row per period with its
RSS, and the verdict on RSS growth. Figures are not asserted: they are the benchmark's."""

from __future__ import annotations

import pytest

import bench.soak
from bench.soak import growth


def test_a_short_soak_has_a_row_per_period_and_the_growth() -> None:
    report, _flat = bench.soak.run(2, 2000, 10.0, row_seconds=2)
    rows = [line.split() for line in report.splitlines() if line.strip()[:1].isdigit()]
    assert [row[0] for row in rows] == ["1", "2"]
    assert all(int(row[1]) == 2 and int(row[5]) > 0 and float(row[7]) > 0 for row in rows)
    assert "RSS growth after the first minute" in report and "errors" not in report


def test_growth_is_the_slope_per_minute() -> None:
    assert growth([100.0, 102.0, 104.0, 106.0]) == pytest.approx(2.0)
    assert growth([100.0, 100.0, 100.0]) == 0.0
    assert growth([100.0]) == 0.0


def test_bad_arguments_are_refused(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exc:
        bench.soak.main(["--minutes", "0"])
    assert exc.value.code == 2
    assert "--minutes must be at least 1" in capsys.readouterr().err
