"""A running benchmark says what it is measuring, on stderr, as it goes: a full run takes minutes,
and the results table (stdout) only comes at the end. Stdout stays the table alone."""

from __future__ import annotations

import sys


def step(bench: str, what: str) -> None:
    print(f"situated bench {bench}: {what}...", file=sys.stderr, flush=True)
