"""The environment of a prefix: its runtime and interfaces first, discovery on this machine."""

from __future__ import annotations

import shlex
import subprocess
from pathlib import Path

from api.ros.prefix import Prefix, environment, exports


def test_the_runtime_and_the_interfaces_come_first_and_the_build_tools_never(tmp_path: Path) -> None:
    prefix = Prefix(tmp_path)
    libs = prefix.site_packages(prefix.runtime) / "ros_rcl.libs"
    libs.mkdir(parents=True)
    env = environment(prefix, {"PYTHONPATH": "/mine", "LD_LIBRARY_PATH": "/usr/local/lib"})
    paths = env["PYTHONPATH"].split(":")
    assert paths == [str(prefix.site_packages(prefix.install)), str(prefix.site_packages(prefix.runtime)), "/mine"]
    assert str(libs) in env["LD_LIBRARY_PATH"].split(":")
    assert env["LD_LIBRARY_PATH"].endswith(":/usr/local/lib")
    assert not any(str(prefix.build) in value for value in env.values())
    assert env["RMW_IMPLEMENTATION"] == "rmw_fastrtps_cpp"


def test_discovery_stays_on_this_machine_unless_the_shell_says_otherwise(tmp_path: Path) -> None:
    assert environment(Prefix(tmp_path), {})["ROS_AUTOMATIC_DISCOVERY_RANGE"] == "LOCALHOST"
    assert environment(Prefix(tmp_path), {"ROS_AUTOMATIC_DISCOVERY_RANGE": "SUBNET"})[
        "ROS_AUTOMATIC_DISCOVERY_RANGE"] == "SUBNET"


def test_exports_are_quoted_for_the_shell(tmp_path: Path) -> None:
    text = exports({"A": "/a b/c", "B": "it's"})
    done = subprocess.run(["sh", "-c", text + 'printf "%s|%s" "$A" "$B"'], capture_output=True, text=True, check=True)
    assert done.stdout == "/a b/c|it's"
    assert text.splitlines()[0] == "export A=" + shlex.quote("/a b/c")
