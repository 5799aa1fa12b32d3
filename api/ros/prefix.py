"""A ROS 2 prefix built by `situated ros install`: its layout and the environment that uses it.

The prefix holds two virtual environments made with the Python that runs situated: ``build`` (the
build tools: ament, the rosidl generators, colcon, and the message packages CMake needs) and
``runtime`` (rclpy, the Fast DDS middleware and the message packages at run time), then the
interface packages colcon built (``install``, merged). Only the runtime and the built interfaces
go on the ``PYTHONPATH``: the build tools (and the pytest, numpy and others they bring) never shadow
the packages of the interpreter that imports rclpy.
"""

from __future__ import annotations

import os
import shlex
import sys
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

#: The environment variables a ROS 2 graph of this machine is kept on. Fast DDS multicasts its
#: discovery on every interface unless told otherwise.
LOCAL_DISCOVERY = "LOCALHOST"


@dataclass(frozen=True)
class Prefix:
    """The folders of one prefix (nothing is created by naming them)."""

    root: Path

    @property
    def build(self) -> Path:
        return self.root / "build"

    @property
    def runtime(self) -> Path:
        return self.root / "runtime"

    @property
    def src(self) -> Path:
        return self.root / "src"

    @property
    def install(self) -> Path:
        return self.root / "install"

    @property
    def work(self) -> Path:
        """colcon's build folder and logs."""
        return self.root / "work"

    @property
    def stamp(self) -> Path:
        """What the last complete install was made from (its key): written last."""
        return self.root / "situated-ros.json"

    def site_packages(self, venv: Path) -> Path:
        return venv / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages"


def _joined(first: list[str], existing: str | None) -> str:
    return os.pathsep.join([*first, *([existing] if existing else [])])


def environment(prefix: Prefix, base: Mapping[str, str] | None = None) -> dict[str, str]:
    """The variables to set (only those) for this interpreter to import rclpy and the interfaces
    of ``prefix``, prepended to what ``base`` (default: this process's environment) has."""
    env = os.environ if base is None else base
    runtime_site = prefix.site_packages(prefix.runtime)
    # The wheels' own shared libraries: the runtime venv's lib/ and each ros_*.libs folder
    # (ros-wheels-bootstrapper's .pth does this only inside that venv, by re-executing Python).
    libs = [str(prefix.install / "lib"), str(prefix.runtime / "lib"),
            *sorted(str(p) for p in runtime_site.glob("ros_*.libs"))]
    return {
        "PYTHONPATH": _joined([str(prefix.site_packages(prefix.install)), str(runtime_site)],
                              env.get("PYTHONPATH")),
        "LD_LIBRARY_PATH": _joined(libs, env.get("LD_LIBRARY_PATH")),
        "AMENT_PREFIX_PATH": _joined([str(prefix.install), str(prefix.runtime)],
                                     env.get("AMENT_PREFIX_PATH")),
        "RMW_IMPLEMENTATION": env.get("RMW_IMPLEMENTATION", "rmw_fastrtps_cpp"),
        # A pip-installed ROS is a developer's: its graph stays on this machine unless the shell
        # already says otherwise.
        "ROS_AUTOMATIC_DISCOVERY_RANGE": env.get("ROS_AUTOMATIC_DISCOVERY_RANGE", LOCAL_DISCOVERY),
    }


def exports(variables: Mapping[str, str]) -> str:
    """``export NAME=value`` lines, quoted for a POSIX shell."""
    return "".join(f"export {name}={shlex.quote(value)}\n" for name, value in variables.items())
