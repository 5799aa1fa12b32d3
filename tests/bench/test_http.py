"""`situated bench http`, short: each endpoint at each client count beside the echo measured in the
same run, and the verdict computed from those rows. Figures are not asserted: they are the
benchmark's."""

from __future__ import annotations

import pytest

import bench.http
from bench.http import ECHO, NAME, TURN_MODEL, TURN_RULES, Result, table


def test_a_short_run_measures_each_endpoint_beside_the_echo_at_each_client_count() -> None:
    report, _ok = bench.http.run(0.3, (1, 3))
    rows = [line for line in report.splitlines() if line.startswith("POST ")]
    assert [(row[:NAME].strip(), row[NAME:].split()[0]) for row in rows] == [
        (name, clients) for clients in ("1", "3") for name in (ECHO, "POST /kb/query", TURN_RULES, TURN_MODEL)]
    assert all(int(row[NAME:].split()[1]) > 0 for row in rows)
    # each row says the server's CPU per request, and the echo's against it
    cpu_ms = [float(row[NAME:].split()[-2]) for row in rows]
    assert all(ms > 0 for ms in cpu_ms)
    assert [row[NAME:].split()[-1] for row in rows if row.startswith(ECHO)] == ["100%", "100%"]
    assert "load average" in report.splitlines()[-1]


def test_the_verdict_takes_each_row_against_the_echo_of_its_client_count() -> None:
    def result(name: str, clients: int, rate: int, p99_ms: float) -> Result:
        return Result(name, clients, rate, 1.0, [p99_ms / 1000] * 99 + [p99_ms / 1000])

    echo_1, echo_8 = result(ECHO, 1, 1000, 1.0), result(ECHO, 8, 400, 2.0)
    fast = [echo_1, result("POST /kb/query", 1, 500, 3.0), echo_8, result("POST /kb/query", 8, 200, 6.0)]
    assert table(fast)[1] is True
    slow_at_8 = [echo_1, result("POST /kb/query", 1, 500, 3.0), echo_8, result("POST /kb/query", 8, 199, 6.0)]
    assert table(slow_at_8)[1] is False
    late_tail = [echo_1, result("POST /kb/query", 1, 900, 3.1)]
    assert table(late_tail)[1] is False


@pytest.mark.parametrize(("args", "says"), [
    (["--clients", "1,x"], "--clients takes numbers separated by commas, not '1,x'"),
    (["--clients", "0"], "each client count at least 1"),
    (["--seconds", "0"], "--seconds must be positive"),
])
def test_bad_arguments_are_refused(args: list[str], says: str, capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exc:
        bench.http.main(args)
    assert exc.value.code == 2
    assert says in capsys.readouterr().err


def test_the_cpu_columns_take_each_row_against_the_echo_of_its_client_count() -> None:
    echo = Result(ECHO, 1, 1000, 1.0, [0.001] * 100, cpu=0.5)  # 0.5 ms of CPU a request
    turn = Result(TURN_RULES, 1, 200, 1.0, [0.004] * 100, cpu=0.4)  # 2 ms
    unread = Result(TURN_MODEL, 1, 100, 1.0, [0.01] * 100)
    report, _ok = table([echo, turn, unread])
    rows = {line[:NAME].strip(): line[NAME:].split()[-2:] for line in report.splitlines()[1:4]}
    assert rows == {ECHO: ["0.50", "100%"], TURN_RULES: ["2.00", "25%"], TURN_MODEL: ["-", "-"]}
