import pytest

import bench.backend


def test_backend_bench_measures_both_backends_both_ways(capsys: pytest.CaptureFixture[str]) -> None:
    assert bench.backend.main(["--turns", "2"]) == 0
    rows = {line.split()[0]: line.split()[1:] for line in capsys.readouterr().out.splitlines()[2:]}
    assert set(rows) == {"openai", "ollama"}
    assert all(len(values) == 2 and all(float(v) > 0 for v in values) for values in rows.values())


def test_backend_bench_refuses_no_turns() -> None:
    with pytest.raises(SystemExit):
        bench.backend.main(["--turns", "0"])
