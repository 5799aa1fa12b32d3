"""`situated ros`: env prints what makes rclpy importable; run says what is missing, in one line."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from api.cli import main
from api.ros.prefix import Prefix
from tests.api.ros.conftest import ROOT


def test_env_on_a_folder_never_built_says_how_to_build_it(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    assert main(["ros", "env", "--prefix", str(tmp_path)]) == 2
    assert f"situated ros install --prefix {tmp_path}" in capsys.readouterr().err


def test_run_without_ros_names_what_is_missing_and_how_to_get_it() -> None:
    env = {name: value for name, value in os.environ.items() if name not in ("PYTHONPATH", "AMENT_PREFIX_PATH")}
    done = subprocess.run([sys.executable, "-m", "api.cli", "ros", "run", "--scene", "none"], capture_output=True,
                          text=True, cwd=ROOT, env=env, timeout=120)
    assert done.returncode == 2
    assert "cannot import rclpy" in done.stderr and "situated ros install --prefix DIR" in done.stderr
    assert "Traceback" not in done.stderr


def test_the_printed_exports_make_rclpy_and_the_interfaces_importable(prefix: Prefix) -> None:
    script = (f'eval "$({sys.executable} -m api.cli ros env --prefix {prefix.root})" && cd / && '
              f"{sys.executable} -c 'import rclpy, kb_msgs.srv, chatbot_msgs.srv, hri_actions_msgs.msg; print(42)'")
    done = subprocess.run(["bash", "-c", script], capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "42"


def test_install_on_a_built_prefix_is_quick_and_changes_nothing(prefix: Prefix) -> None:
    before = prefix.stamp.stat().st_mtime_ns
    done = subprocess.run([sys.executable, "-m", "api.cli", "ros", "install", "--prefix", str(prefix.root)],
                          capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert done.returncode == 0 and "up to date" in done.stderr
    assert prefix.stamp.stat().st_mtime_ns == before
