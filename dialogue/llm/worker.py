"""A model runner in a process of its own, so that a native crash ends that process, not the service.

llama.cpp is native code: a segfault or an abort in it (a CPU kernel the machine cannot run, a bug)
kills whatever process runs it. `ProcessWorker` runs the runner in one child process, started with
the *spawn* method (no fork of a threaded parent), and talks to it over a pipe, one request at a
time (the caller serialises). The child is kept and reused, so whatever the runner caches (the
loaded model, llama.cpp's prompt-prefix KV cache) survives from one request to the next. A streamed
generation sends its text in `("chunk", text)` messages before the one reply.

A request the child never answers — it died, or it outlived the request's time limit and was
killed — raises `WorkerCrashed`, saying how the child ended (the signal's name or the exit status);
the next request starts a new child. Cancellation crosses the process boundary through one shared
integer, the id of the job to stop, which the runner's generation checks after every token.
"""

from __future__ import annotations

import contextlib
import signal
import time
from collections.abc import Callable
from dataclasses import dataclass
from multiprocessing import get_context
from multiprocessing.connection import Connection, wait
from multiprocessing.process import BaseProcess
from typing import Any, Protocol

from dialogue.llm.base import ModelError

#: Seconds a stopping child gets to close its model before it is killed.
STOP_TIMEOUT = 10.0


@dataclass(frozen=True)
class Completion:
    """What one generation returns across the pipe."""

    text: str
    finish_reason: str | None
    prompt_tokens: int | None = None
    completion_tokens: int | None = None
    #: Prompt tokens whose evaluation was reused from the previous request (the KV-cache prefix).
    cached_tokens: int | None = None


class Runner(Protocol):
    """What runs in the child: loads a model and generates. Errors it means are `ModelError`s."""

    def load(self) -> None: ...

    def info(self) -> str: ...

    def generate(
        self,
        messages: list[dict[str, str]],
        schema: dict[str, Any],
        expired: Callable[[], bool],
        emit: Callable[[str], None] | None = None,
    ) -> Completion: ...

    def close(self) -> None: ...


class WorkerCrashed(ModelError):
    """The worker process died (or hung and was killed) before it answered."""


# --- the child ------------------------------------------------------------------------------------------

Emit = Callable[[str], None]


def _load(runner: Runner, args: tuple[Any, ...], expired: Callable[[], bool], emit: Emit) -> None:
    runner.load()


def _info(runner: Runner, args: tuple[Any, ...], expired: Callable[[], bool], emit: Emit) -> str:
    return runner.info()


def _generate(runner: Runner, args: tuple[Any, ...], expired: Callable[[], bool], emit: Emit) -> Completion:
    messages, schema = args
    return runner.generate(messages, schema, expired)


def _stream(runner: Runner, args: tuple[Any, ...], expired: Callable[[], bool], emit: Emit) -> Completion:
    messages, schema = args
    return runner.generate(messages, schema, expired, emit)


OPERATIONS: dict[str, Callable[[Runner, tuple[Any, ...], Callable[[], bool], Emit], Any]] = {
    "load": _load,
    "info": _info,
    "generate": _generate,
    "stream": _stream,
}


def serve(
    conn: Connection, cancelled: Any, factory: Callable[[], Runner], setup: Callable[[], None] | None
) -> None:
    """The child's main loop: one request in, one reply out, until `stop` or the parent goes away."""
    # Ctrl-C in a terminal reaches the whole process group; the parent decides when this child stops.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if setup is not None:
        setup()
    runner = factory()
    try:
        while True:
            try:
                op, job_id, budget, args = conn.recv()
            except EOFError:  # the parent died or closed the pipe
                return
            if op == "stop":
                return
            deadline = None if budget is None else time.monotonic() + budget

            def expired(job: int = job_id, until: float | None = deadline) -> bool:
                return bool(cancelled.value == job) or (until is not None and time.monotonic() >= until)

            def emit(text: str) -> None:
                conn.send(("chunk", text))

            try:
                reply: tuple[str, Any] = ("ok", OPERATIONS[op](runner, args, expired, emit))
            except ModelError as exc:  # the runner's own verdicts travel back; anything else kills us
                reply = ("raise", exc)
            try:
                conn.send(reply)
            except (BrokenPipeError, ConnectionResetError):
                return
    finally:
        runner.close()


# --- the parent ---------------------------------------------------------------------------------------


def describe_exit(code: int | None) -> str:
    if code is None:
        return "did not exit"
    if code < 0:
        try:
            return f"was killed by {signal.Signals(-code).name}"
        except ValueError:
            return f"was killed by signal {-code}"
    return f"exited with status {code}"


class ProcessWorker:
    """The parent's handle on one child process. Not thread-safe: call it from one thread."""

    def __init__(
        self,
        factory: Callable[[], Runner],
        *,
        setup: Callable[[], None] | None = None,
        name: str = "model worker",
    ) -> None:
        self._factory = factory
        self._setup = setup
        self.name = name
        self._context = get_context("spawn")
        self._process: BaseProcess | None = None
        self._conn: Connection | None = None
        self._cancelled: Any = None
        #: How many times a child died or was killed; what happened the last time.
        self.crashes = 0
        self.last_crash: str | None = None

    @property
    def pid(self) -> int | None:
        return self._process.pid if self._process is not None else None

    @property
    def alive(self) -> bool:
        return self._process is not None and self._process.is_alive()

    def start(self) -> None:
        """Start the child unless it runs. Blocking (a spawn imports Python afresh: ~0.2-1 s)."""
        if self._process is not None:
            return
        if self._cancelled is None:
            self._cancelled = self._context.RawValue("q", 0)
        parent, child = self._context.Pipe()
        process = self._context.Process(
            target=serve, args=(child, self._cancelled, self._factory, self._setup),
            name=self.name, daemon=True,
        )  # fmt: skip
        process.start()
        child.close()
        self._process, self._conn = process, parent

    def cancel(self, job_id: int) -> None:
        """Stop job `job_id` at its next token (thread-safe: one shared integer)."""
        if self._cancelled is not None:
            self._cancelled.value = job_id

    def call(
        self,
        op: str,
        args: tuple[Any, ...] = (),
        *,
        job_id: int = 0,
        budget: float | None = None,
        limit: float | None = None,
        on_chunk: Callable[[str], None] | None = None,
    ) -> Any:
        """Run `op` in the child and return its result, or raise what the runner raised.

        `budget` is the job's time left (the runner stops at it); `limit` is how long to wait for the
        answer before the child is considered hung and killed (None: wait as long as it lives).
        `on_chunk` gets the text a streaming op sends before its reply; it must not raise.
        """
        self.start()
        process, conn = self._process, self._conn
        assert process is not None and conn is not None
        try:
            conn.send((op, job_id, budget, args))
        except (BrokenPipeError, ConnectionResetError):
            self._died(op)
        until = None if limit is None else time.monotonic() + limit
        while True:
            left = None if until is None else max(0.0, until - time.monotonic())
            ready = wait([conn, process.sentinel], left)
            if not ready:
                process.kill()
                self._died(op, f"did not answer within {limit:.1f} s and was killed")
            if conn not in ready:
                self._died(op)
            try:
                kind, value = conn.recv()
            except (EOFError, ConnectionResetError):
                self._died(op)
            if kind != "chunk":
                break
            if on_chunk is not None:
                on_chunk(value)
        if kind == "raise":
            raise value
        return value

    def _died(self, op: str, how: str | None = None) -> Any:
        process, conn = self._process, self._conn
        self._process = self._conn = None
        pid: int | None = None
        code: int | None = None
        if process is not None:
            pid = process.pid
            process.join(STOP_TIMEOUT)
            if process.exitcode is None:  # the pipe broke but the process lingers
                process.kill()
                process.join()
            code = process.exitcode
            process.close()
        if conn is not None:
            conn.close()
        message = f"the {self.name} process (pid {pid}) {how or describe_exit(code)} during {op}"
        self.crashes += 1
        self.last_crash = message
        raise WorkerCrashed(message)

    def stop(self) -> None:
        """Ask the child to close its runner and exit; kill it if it does not in time."""
        process, conn = self._process, self._conn
        self._process = self._conn = None
        if process is None or conn is None:
            return
        with contextlib.suppress(BrokenPipeError, ConnectionResetError):  # already gone
            conn.send(("stop", 0, None, ()))
        process.join(STOP_TIMEOUT)
        if process.exitcode is None:
            process.kill()
            process.join()
        conn.close()
        process.close()
