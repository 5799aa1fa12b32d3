"""knowledge_core 3.5's own ROS tests, run unchanged against situated's node over a real graph.

Each vendored file (tests/api/ros/knowledge_core_350, Apache-2.0) runs with pytest in a subprocess
under the ROS environment, in the test's own domain, against a fresh `situated ros run --scene none`
(knowledge_core starts empty too). Only the transport is adapted, by stand-ins on the subprocess's
path (``standins/``): ``launch``, ``launch_ros`` and ``launch_testing`` make the launch description
inert (the fixture starts the node; the post-shutdown exit-code tests are skipped, and this test
checks how the node stops instead), ``knowledge_core.api`` is situated's ROS client
(``api.ros.client.kb``), and the ``situated_discovery`` plugin gives DDS discovery the few seconds
it takes here where the tests give it 1 s. No assertion is changed.

Every test must pass, except the known differences of situated listed in ``EXPECTED``, each with
the text that shows its reason in the failure. The outcome of every test is printed.
"""

from __future__ import annotations

import shutil
import signal
import subprocess
import sys
import xml.etree.ElementTree as ElementTree
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import pytest

from tests.api.ros.conftest import ROOT, RosNode

UPSTREAM = Path(__file__).with_name("knowledge_core_350")
STANDINS = UPSTREAM / "standins"
#: Seconds one file's tests may take (the events file waits on purpose: about 20 s).
RUN_TIMEOUT = 600


@dataclass(frozen=True)
class Expected:
    """A known difference: why the test fails, and texts of its failure that show that reason."""

    reason: str
    shows: tuple[str, ...]


#: Test id (file::class::test) -> why it fails against situated.
EXPECTED: dict[str, Expected] = {
    # kb-compat K1: situated's rows are distinct, where knowledge_core's `vars=["?cls"]` answer
    # repeats {"cls": "Agent"} (once per subclass).
    "test_ros_350.py::TestKB::test_queries": Expected(
        "situated's rows are distinct (kb-compat K1)", ("First has 1, Second has 2:  {'cls': 'Agent'}",)),
    # kb-compat §1.4: single-quoted literals are refused upstream; accepting them is allowed.
    "test_pythonic_api_ros_350.py::TestPythonicROSKb::test_literals": Expected(
        "situated accepts the single-quoted literal 'test' (kb-compat §1.4 allows it)",
        ("KbError not raised", "test_pythonic_api_ros_350.py:291: AssertionError")),
}
#: The post-shutdown tests (the launched process's exit code): skipped by the stand-in.
SKIPPED = "post-shutdown test of the launched process"


@dataclass(frozen=True)
class Outcome:
    test: str
    result: str  # passed, failed, skipped
    text: str


def run_upstream(name: str, env: dict[str, str], work: Path) -> list[Outcome]:
    """Run one vendored file with pytest under ROS; the outcome of each of its tests."""
    work.mkdir()
    shutil.copy(UPSTREAM / name, work / name)
    (work / "pytest.ini").write_text("[pytest]\nmarkers =\n    rostest: a ROS launch test\n")
    report = work / "report.xml"
    path = [str(STANDINS), str(ROOT), env.get("PYTHONPATH", "")]
    command = [sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-p", "situated_discovery",
               "-c", str(work / "pytest.ini"),
               "--rootdir", str(work), f"--junitxml={report}", "-q", "-rA", name]
    with (work / "pytest.log").open("wb") as log:
        done = subprocess.run(command, cwd=work, env={**env, "PYTHONPATH": ":".join(path)}, stdout=log,
                              stderr=subprocess.STDOUT, timeout=RUN_TIMEOUT, check=False)
    output = (work / "pytest.log").read_text(errors="replace")
    assert report.is_file(), f"pytest wrote no report (exit {done.returncode}):\n{output[-4000:]}"
    return outcomes(name, report)


def outcomes(name: str, report: Path) -> list[Outcome]:
    found = []
    for case in ElementTree.parse(report).getroot().iter("testcase"):
        test = f"{name}::{case.get('classname', '').rsplit('.', 1)[-1]}::{case.get('name')}"
        result, text = "passed", ""
        for child in case:
            if child.tag in ("failure", "error"):
                result, text = "failed", f"{child.get('message', '')}\n{child.text or ''}"
            elif child.tag == "skipped":
                result, text = "skipped", child.get("message", "")
        found.append(Outcome(test, result, text))
    return found


def unexpected(outcome: Outcome) -> str | None:
    """What is wrong with an outcome, if anything."""
    expected = EXPECTED.get(outcome.test)
    if outcome.result == "skipped":
        return None if SKIPPED in outcome.text else f"{outcome.test} skipped: {outcome.text}"
    if expected is None:
        return None if outcome.result == "passed" else f"{outcome.test} failed:\n{outcome.text}"
    if outcome.result != "failed":
        return f"{outcome.test} passes now: remove it from EXPECTED"
    if not all(text in outcome.text for text in expected.shows):
        return f"{outcome.test} fails for another reason than {expected.reason}:\n{outcome.text}"
    return None


def table(found: list[Outcome]) -> str:
    lines = [f"{o.result:8} {o.test}" + (f"  [{EXPECTED[o.test].reason}]" if o.test in EXPECTED else "")
             for o in found]
    counts = {r: sum(o.result == r for o in found) for r in ("passed", "failed", "skipped")}
    return "\n".join([*lines, ", ".join(f"{n} {r}" for r, n in counts.items())])


@pytest.mark.parametrize("name", ["test_ros_350.py", "test_ros_events_350.py", "test_pythonic_api_ros_350.py"])
def test_knowledge_cores_own_tests_against_our_node(name: str, ros_node_factory: Callable[..., RosNode],
                                                   ros_env: dict[str, str], tmp_path: Path) -> None:
    node = ros_node_factory("--scene", "none")
    found = run_upstream(name, ros_env, tmp_path / "upstream")
    print(f"\nknowledge_core 3.5's {name} against situated's node:\n{table(found)}")
    assert found, "no test ran"
    wrong = [problem for outcome in found if (problem := unexpected(outcome))]
    assert not wrong, "\n".join(wrong) + f"\n\n{table(found)}"
    # What the skipped post-shutdown tests check of knowledge_core's process: the node stops cleanly.
    node.server.proc.send_signal(signal.SIGTERM)
    assert node.server.proc.wait(30) == -signal.SIGTERM
    log = node.server.log.read_text()
    assert "Application shutdown complete" in log and "Traceback" not in log
