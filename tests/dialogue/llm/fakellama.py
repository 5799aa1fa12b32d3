"""A fake `llama_cpp` for the worker process, steered and observed through files.

`install(folder)` runs first in the worker process (LlamaCppModel's `worker_setup`) and puts the fake
modules in its sys.modules. The fake reads `folder/config.json` at every load and completion, so a
test changes its behaviour between turns with `FakeControl.set(...)`, and appends what it did to
`folder/events.jsonl` (loads, grammars, tokens generated, closes), read with `FakeControl.events()`.
Its Llama generates tokens one by one, checking the stopping criterion after each like the real one,
so the time-budget machinery is exercised for real; `crash` makes it die like native code does. With
`stream=True` it yields the answer in `tokens` pieces, one per token; like the real one it keeps the
evaluated tokens (`input_ids[:n_tokens]`), so the prefix a next prompt shares is known, and `reset()`
forgets them.
"""

from __future__ import annotations

import json
import os
import signal
import sys
import time
import types
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from tests.dialogue.llm.common import ANSWER

DEFAULTS: dict[str, Any] = {
    "answer": ANSWER,
    "finish_reason": "stop",
    "tokens": 5,
    "per_token": 0.0,
    "load_error": None,
    "metadata_template": "{{ messages }}",
    "grammar_fail": False,
    #: "abort", "segv" or "exit": how the worker dies; "crash_at": "load" or "generate".
    "crash": None,
    "crash_at": "generate",
}

CRASHES = {
    "abort": os.abort,
    "segv": lambda: os.kill(os.getpid(), signal.SIGSEGV),
    "exit": lambda: os._exit(3),
}


@dataclass
class FakeControl:
    folder: Path

    def set(self, **values: Any) -> None:
        unknown = set(values) - set(DEFAULTS)
        assert not unknown, unknown
        path = self.folder / "config.json"
        config = json.loads(path.read_text()) if path.exists() else {}
        path.write_text(json.dumps({**config, **values}))

    def events(self, kind: str | None = None) -> list[dict[str, Any]]:
        path = self.folder / "events.jsonl"
        rows = [json.loads(line) for line in path.read_text().splitlines()] if path.exists() else []
        return [row for row in rows if kind is None or row["event"] == kind]


def _config(folder: Path) -> dict[str, Any]:
    path = folder / "config.json"
    return {**DEFAULTS, **(json.loads(path.read_text()) if path.exists() else {})}


def _record(folder: Path, event: str, **data: Any) -> None:
    with (folder / "events.jsonl").open("a") as out:
        out.write(json.dumps({"event": event, "pid": os.getpid(), **data}) + "\n")


def _maybe_crash(config: dict[str, Any], where: str) -> None:
    if config["crash"] and config["crash_at"] == where:
        sys.stderr.flush()
        CRASHES[config["crash"]]()


def install(folder_name: str) -> None:  # noqa: C901
    """Runs in the worker process: make `import llama_cpp` find the fake."""
    folder = Path(folder_name)

    class FakeLlama:
        def __init__(self, model_path: str, **kwargs: Any) -> None:
            config = _config(folder)
            _maybe_crash(config, "load")
            if config["load_error"]:
                raise ValueError(config["load_error"])
            template = config["metadata_template"]
            self.metadata = {"tokenizer.chat_template": template} if template else {}
            self.input_ids: list[int] = []
            self.n_tokens = 0
            _record(folder, "load", model_path=model_path, n_ctx=kwargs["n_ctx"], n_threads=kwargs["n_threads"])

        def token_eos(self) -> int:
            return 2

        def token_bos(self) -> int:
            return 1

        def detokenize(self, tokens: list[int], special: bool = False) -> bytes:
            return b"<eos>" if tokens == [2] else b"<bos>"

        def tokenize(self, text: bytes, add_bos: bool = True, special: bool = False) -> list[int]:
            return [sum(word) for word in text.split()]  # the same words are the same tokens

        def reset(self) -> None:
            self.n_tokens = 0
            _record(folder, "reset")

        def create_completion(self, **kwargs: Any) -> Any:
            config = _config(folder)
            _maybe_crash(config, "generate")
            self.input_ids = [*kwargs["prompt"], *range(1000, 1000 + config["tokens"])]
            self.n_tokens = len(self.input_ids)
            _record(folder, "completion", grammar=kwargs["grammar"] is not None, stream=kwargs["stream"])
            if kwargs["stream"]:
                return self._stream(config, kwargs)
            for n in range(1, config["tokens"] + 1):
                time.sleep(config["per_token"])
                if kwargs["stopping_criteria"]([n], None):
                    _record(folder, "generated", tokens=n)
                    return {"choices": [{"text": "{", "finish_reason": "stop"}]}
            _record(folder, "generated", tokens=config["tokens"])
            return {
                "choices": [{"text": config["answer"], "finish_reason": config["finish_reason"]}],
                "usage": {"completion_tokens": config["tokens"], "prompt_tokens": len(kwargs["prompt"])},
            }

        def _stream(self, config: dict[str, Any], kwargs: dict[str, Any]) -> Iterator[dict[str, Any]]:
            answer, tokens = config["answer"], config["tokens"]
            size = -(-len(answer) // tokens)
            for n in range(1, tokens + 1):
                time.sleep(config["per_token"])
                if kwargs["stopping_criteria"]([n], None):
                    _record(folder, "generated", tokens=n)
                    yield {"choices": [{"text": "", "finish_reason": "stop"}]}
                    return
                last = n == tokens
                yield {"choices": [{"text": answer[(n - 1) * size : n * size],
                                    "finish_reason": config["finish_reason"] if last else None}]}
            _record(folder, "generated", tokens=tokens)

        def close(self) -> None:
            _record(folder, "close")

    class FakeFormatter:
        def __init__(self, **kwargs: Any) -> None:
            self.kwargs = kwargs
            _record(folder, "formatter", template=kwargs["template"])

        def __call__(self, *, messages: list[dict[str, str]]) -> Any:
            prompt = " ".join(m["content"] for m in messages)
            return types.SimpleNamespace(prompt=prompt, stop=["<eos>"], stopping_criteria=None, added_special=True)

    class FakeGrammar:
        @classmethod
        def from_json_schema(cls, schema: str, verbose: bool = True) -> FakeGrammar:
            if _config(folder)["grammar_fail"]:
                raise ValueError("unsupported schema keyword")
            _record(folder, "grammar", schema=schema)
            return cls()

    module = types.ModuleType("llama_cpp")
    module.Llama = FakeLlama  # type: ignore[attr-defined]
    module.llama_print_system_info = lambda: b"CPU : AVX = 1 | AVX2 = 1 | FAKE = 1 |"  # type: ignore[attr-defined]
    grammar = types.ModuleType("llama_cpp.llama_grammar")
    grammar.LlamaGrammar = FakeGrammar  # type: ignore[attr-defined]
    module.llama_grammar = grammar  # type: ignore[attr-defined]
    module.llama_chat_format = types.SimpleNamespace(Jinja2ChatFormatter=FakeFormatter)  # type: ignore[attr-defined]
    sys.modules["llama_cpp"] = module
    sys.modules["llama_cpp.llama_grammar"] = grammar
    try:
        import jinja2  # noqa: F401  (a dependency of llama-cpp-python: absent without the extra)
    except ImportError:
        fake_jinja2 = types.ModuleType("jinja2")
        fake_jinja2.TemplateError = type("TemplateError", (Exception,), {})  # type: ignore[attr-defined]
        sys.modules["jinja2"] = fake_jinja2


def install_missing() -> None:
    """Runs in the worker process: llama-cpp-python is not installed."""
    sys.modules["llama_cpp"] = None  # type: ignore[assignment]
