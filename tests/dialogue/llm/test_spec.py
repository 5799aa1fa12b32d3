import pytest

from dialogue.llm.hybrid import HybridModel
from dialogue.llm.ollama import OllamaModel
from dialogue.llm.openai import OpenAIModel
from dialogue.llm.rules import RulesModel
from dialogue.llm.spec import SpecError, parse_spec


def test_rules() -> None:
    backend = parse_spec("rules")
    assert isinstance(backend.model, RulesModel) and backend.spec == "rules"


def test_ollama_specs() -> None:
    plain = parse_spec("ollama:gemma3:1b").model
    assert (
        isinstance(plain, OllamaModel)
        and plain.model == "gemma3:1b"
        and plain.host == "http://127.0.0.1:11434"
    )
    remote = parse_spec("ollama:gemma3:1b@http://gpu:11434").model
    assert isinstance(remote, OllamaModel) and (remote.model, remote.host) == (
        "gemma3:1b",
        "http://gpu:11434",
    )


def test_openai_and_hybrid_specs() -> None:
    backend = parse_spec("hybrid:openai:qwen2.5@http://h:8080/v1")
    assert isinstance(backend.model, HybridModel) and isinstance(backend.model.inner, OpenAIModel)
    inner = backend.model.inner
    assert (inner.model, inner.base_url) == ("qwen2.5", "http://h:8080/v1")
    assert inner.options.response_format == "json_schema"
    assert backend.model.llm is inner and backend.spec == "hybrid:openai:qwen2.5@http://h:8080/v1"
    other = parse_spec("openai-json:m@http://h/v1").model
    assert isinstance(other, OpenAIModel) and other.options.response_format == "json_object"


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("gpt", "bad backend spec"),
        ("claude:opus", "unknown backend 'claude'"),
        ("ollama:", "model name is missing"),
        ("ollama:gemma3@localhost:11434", "must be an http"),
        ("hybrid:rules", "hybrid needs an LLM spec"),
        ("hybrid:hybrid:ollama:x", "hybrid needs an LLM spec"),
    ],
)
def test_bad_specs_say_what_is_wrong(spec: str, message: str) -> None:
    with pytest.raises(SpecError, match=message):
        parse_spec(spec)
