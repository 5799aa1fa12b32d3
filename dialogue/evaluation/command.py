"""`situated eval`: score a case file, or compare the tutorial's approach with the engine.

It sits above `cases` and `compare` (both import `cases`), so neither imports the other's command.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from importlib.resources import as_file, files
from pathlib import Path

from dialogue.evaluation.cases import EvalError, format_report, run
from dialogue.evaluation.compare import compare, format_comparison

#: The set run when no file is given: in the resource package `eval` (eval/huric/ in a clone), so an
#: installed copy has it too.
DEFAULT_SET = ("huric", "dev.jsonl")


def default_cases() -> Path:
    """The shipped HuRIC development set (a file on disk: its scenes are read beside it)."""
    with as_file(files("eval").joinpath(*DEFAULT_SET)) as path:
        return path


def main(argv: Sequence[str] | None = None, guide: str = "") -> int:
    """``guide``: the page that explains the command, named by its errors and help (the CLI's)."""
    said = f" (see {guide})" if guide else ""
    parser = argparse.ArgumentParser(prog="situated eval", description="Score dialogue cases (.jsonl).",
                                     epilog=f"The case format and the sets: {guide}" if guide else None)
    parser.add_argument("cases", nargs="?", help="cases file; scenes are read from scenes/ next to it "
                        "(default: the HuRIC development set shipped in eval/huric/dev.jsonl)")
    parser.add_argument("--llm", default="rules", help="backend spec (default: rules)")
    parser.add_argument("--deadline", type=float, default=5.0, help="seconds per turn (default 5)")
    parser.add_argument("--json", action="store_true", help="end with one JSON line of results")
    parser.add_argument(
        "--compare",
        metavar="FILE",
        help="run FILE's cases with the reference tutorial's approach and with situated's engine, "
        "same model, and print both scores and ungrounded referents side by side",
    )
    parser.add_argument("--hybrid", action="store_true", help="with --compare: the engine runs rules first")
    args = parser.parse_args(argv)
    if args.cases is not None and args.compare is not None:
        parser.error("give a cases file or --compare FILE, not both")
    if args.hybrid and args.compare is None:
        parser.error("--hybrid goes with --compare (use a 'hybrid:' spec to evaluate hybrid mode)")
    if args.compare is not None:
        try:
            comparison = compare(args.compare, args.llm, deadline=args.deadline, hybrid=args.hybrid)
        except (EvalError, ValueError) as exc:
            print(f"error: {exc}{said}", file=sys.stderr)
            return 2
        print(format_comparison(comparison))
        if args.json:
            print(json.dumps(comparison.summary()))
        return 0
    if args.cases is None:
        args.cases = default_cases()
        print(f"situated eval: the HuRIC development set, {args.cases}", file=sys.stderr)
    try:
        report = run(args.cases, args.llm, deadline=args.deadline)
    except (EvalError, ValueError) as exc:
        print(f"error: {exc}{said}", file=sys.stderr)
        return 2
    print(format_report(report))
    if args.json:
        print(json.dumps(report.summary()))
    return 0
