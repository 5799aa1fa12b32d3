"""Every shell example of the README and the guides (docs/*.md) runs, and prints what the page shows.

How a page writes a shell example (the convention this test reads):

- A ```` ```console ```` block is run. Each line starting with ``$ `` is a command (a line ending
  with ``\\``, or inside an open quote, continues it on the next); the lines after it, up to the next ``$ `` line, are what it
  prints. Output is compared as doctest compares it (``doctest.ELLIPSIS``): ``...`` in the page
  stands for any text, so ids, times and long answers are written ``"id":"..."``. A command that
  prints nothing shows nothing. A command that must fail ends its output with ``[exit N]``.
- The commands of one page run in order, in a shell (bash) at the repository's root, with this
  environment's ``situated`` first on the PATH and against one real server the test starts for the
  page: ``situated serve`` on a free port of 127.0.0.1 with the offline rules and the demo scene, a
  data directory of its own; the page's ``localhost:8000`` is that server's address, and its
  ``--port 8999`` (a port the page means nothing listens on) a port free at the time.
- Any other shell block (```` ```sh ````, for commands that install things or run until stopped)
  is not run, and must say why on the line before it: ``<!-- not run: REASON -->``.
- A ``console`` block that needs a tool the default suite does not have says so on the line before
  it: ``<!-- needs: ollama -->`` (an ollama server answering at 127.0.0.1:11434 with gemma3:1b) or
  ``<!-- needs: ros -->`` (ROS 2 interfaces built at ``$SITUATED_ROS_PREFIX``, as tests/api/ros use);
  it is skipped, saying so, only when that tool is absent. ``<!-- waits for: BRANCH -->`` skips a
  block documenting what a branch not yet merged adds.
"""

from __future__ import annotations

import doctest
import os
import re
import shlex
import shutil
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

import httpx
import pytest

from bench.oxigraph import free_port
from tests.reliability.server import ServerProcess

ROOT = Path(__file__).parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
_OPEN = re.compile(r"^(```+)([a-z]*)")
_MARK = re.compile(r"<!--\s*(not run|needs|waits for):\s*(.*?)\s*-->\s*$")
_SHELL = {"console", "sh", "bash", "shell"}
_EXIT = re.compile(r"^\[exit (\d+)\]$")
SERVER = "localhost:8000"
OLLAMA = "http://127.0.0.1:11434"


@dataclass
class Command:
    text: str
    expected: str
    status: int = 0


@dataclass
class Block:
    page: str
    line: int
    lang: str
    mark: tuple[str, str] | None
    commands: list[Command] = field(default_factory=list)


def _closed(text: str) -> bool:
    """Whether a command's quotes are closed (a quoted JSON body may span lines)."""
    try:
        shlex.split(text)
    except ValueError:
        return False
    return True


def _commands(body: str) -> list[Command]:
    commands: list[Command] = []
    lines = body.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        if not line.startswith("$ "):
            raise ValueError(f"console block line {line!r} is neither a command nor its output")
        text = line[2:]
        while text.endswith("\\") or not _closed(text):
            i += 1
            text += "\n" + lines[i]
        i += 1
        output: list[str] = []
        while i < len(lines) and not lines[i].startswith("$ "):
            output.append(lines[i])
            i += 1
        status = 0
        if output and (m := _EXIT.match(output[-1])):
            status, output = int(m.group(1)), output[:-1]
        commands.append(Command(text, "\n".join(output), status))
    return commands


def blocks(page: Path) -> list[Block]:
    """The shell blocks of a page, each with the mark on the line before it."""
    lines = page.read_text(encoding="utf-8").splitlines()
    found, i = [], 0
    while i < len(lines):
        fence = _OPEN.match(lines[i])
        if not fence:
            i += 1
            continue
        end = next((j for j in range(i + 1, len(lines)) if lines[j] == fence.group(1)), None)
        assert end is not None, f"{page.name}:{i + 1}: a code block that is never closed"
        if fence.group(2) in _SHELL:
            mark = _MARK.search(lines[i - 1]) if i else None
            block = Block(page.name, i + 1, fence.group(2), (mark.group(1), mark.group(2)) if mark else None)
            if block.lang == "console":
                block.commands = _commands("\n".join(lines[i + 1:end]))
            found.append(block)
        i = end + 1
    return found


def test_the_convention_reads_commands_outputs_and_marks() -> None:
    body = '$ curl -s x \\\n     -d y\n{"a": ...}\n$ situated kb add\n$ false\n[exit 1]\n$ echo \'{"a":\n  1}\'\n{"a":\n'
    assert [(c.text, c.expected, c.status) for c in _commands(body)] == [
        ("curl -s x \\\n     -d y", '{"a": ...}', 0), ("situated kb add", "", 0), ("false", "", 1),
        ("echo '{\"a\":\n  1}'", '{"a":', 0)]
    with pytest.raises(ValueError, match="neither a command"):
        _commands("output before any command\n")


def test_every_shell_block_is_run_or_says_why_not() -> None:
    unmarked = [f"{b.page}:{b.line}" for page in PAGES for b in blocks(page)
                if b.lang != "console" and (b.mark is None or b.mark[0] != "not run" or not b.mark[1])]
    assert unmarked == [], "shell blocks that are not run and do not say why (<!-- not run: REASON -->)"


def _missing(mark: tuple[str, str] | None) -> str | None:
    """Why a block cannot run here, or None."""
    if mark is None or mark[0] == "not run":
        return None
    kind, what = mark
    if kind == "waits for":
        return f"waits for {what} (documents what it adds; not merged yet)"
    if what == "ros":
        prefix = os.environ.get("SITUATED_ROS_PREFIX")
        return None if prefix and Path(prefix).is_dir() else "needs ROS 2: set SITUATED_ROS_PREFIX (situated ros install)"
    if what == "ollama":
        try:
            models = httpx.get(OLLAMA + "/api/tags", timeout=2).json().get("models", [])
        except (httpx.HTTPError, ValueError):
            return f"needs an ollama server at {OLLAMA}"
        if not any(m.get("name", "").startswith("gemma3:1b") for m in models):
            return "needs gemma3:1b in ollama (ollama pull gemma3:1b)"
        return None
    raise AssertionError(f"unknown mark {mark}")


_RUNNABLE = [p for p in PAGES if any(b.lang == "console" for b in blocks(p))]


@pytest.mark.parametrize("page", _RUNNABLE, ids=[p.name for p in _RUNNABLE])
def test_the_page_examples_print_what_the_page_shows(page: Path, tmp_path: Path) -> None:
    runnable = [b for b in blocks(page) if b.lang == "console"]
    skipped = [(b, why) for b in runnable if (why := _missing(b.mark))]
    runnable = [b for b in runnable if not _missing(b.mark)]
    server = None
    if any(SERVER in c.text for b in runnable for c in b.commands):
        server = ServerProcess(["--llm", "rules", "--data", str(tmp_path / "data")], tmp_path / "server.log")
        server.wait_ready()
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}:{os.environ['PATH']}",
           "SITUATED_LLM": "rules", "NO_COLOR": "1"}
    checker, failures = doctest.OutputChecker(), []
    try:
        for block in runnable:
            for command in block.commands:
                text = command.text.replace(SERVER, server.url.removeprefix("http://")) if server else command.text
                text = text.replace("--port 8999", f"--port {free_port()}")
                if block.mark == ("needs", "ros"):  # the prefix the ROS tests built, not the page's .ros
                    text = text.replace("--prefix .ros", '--prefix "$SITUATED_ROS_PREFIX"')
                done = subprocess.run(["bash", "-c", text], cwd=ROOT, env=env, capture_output=True, text=True,
                                      timeout=120, check=False)
                got = "\n".join(line.rstrip() for line in done.stdout.strip("\n").splitlines())
                want = "\n".join(line.rstrip() for line in command.expected.strip("\n").splitlines())
                if done.returncode != command.status or not checker.check_output(
                        want + "\n", got + "\n", doctest.ELLIPSIS):
                    failures.append(f"{page.name}:{block.line}: $ {command.text}\nexpected (exit "
                                    f"{command.status}):\n{want}\ngot (exit {done.returncode}):\n{got}\n"
                                    f"{done.stderr[-2000:]}")
    finally:
        if server:
            server.stop()
    assert not failures, "\n\n".join(failures)
    if skipped:
        pytest.skip("; ".join(f"{page.name}:{b.line}: {why}" for b, why in skipped))


def test_a_missing_tool_is_said_not_ignored(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("SITUATED_ROS_PREFIX", raising=False)
    assert _missing(("needs", "ros")) == "needs ROS 2: set SITUATED_ROS_PREFIX (situated ros install)"
    assert _missing(("waits for", "h/smalls")) == "waits for h/smalls (documents what it adds; not merged yet)"
    assert _missing(None) is None
    assert shutil.which("bash"), "the examples run in bash"
