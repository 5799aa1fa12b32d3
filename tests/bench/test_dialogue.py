"""`situated bench dialogue`, short: each measure with its median wall and CPU time, and the load
beside them. Figures are not asserted: they are the benchmark's."""

from __future__ import annotations

import bench.dialogue


def test_each_measure_gives_its_wall_and_cpu_time_beside_the_load() -> None:
    report = bench.dialogue.run(n_objects=50, repeat=10)  # its answer names obj_042
    head, columns, *rows = report.splitlines()
    assert "load average" in head
    assert columns.split() == ["wall", "cpu"]
    assert [row.split("  ")[1].split(" (")[0] for row in rows] == [
        "overhead, warm", "overhead, KB changed since last turn", "rules fast path", "full rules turn"]
    for row in rows:
        wall, cpu = (float(x) for x in row.split()[-2:])
        assert wall > 0 and cpu > 0
