"""The `openai-json` backend against a real `llama_cpp.server` serving the packaged SmolLM2."""

from __future__ import annotations

import asyncio
import time

from dialogue.engine import DialogueEngine, EngineConfig
from dialogue.llm.base import ChatRequest
from dialogue.llm.openai import OpenAIModel
from dialogue.llm.spec import parse_spec
from dialogue.schema import parse_answer
from tests.dialogue.conftest import scene_kb
from tests.realmodel.checks import assert_grounded
from tests.realmodel.conftest import REALMODEL

pytestmark = REALMODEL
SPEAKER = "person_alice"
#: Generous: a SmolLM2 turn took 7-13 s on 2 cores at load 7 (`situated bench model`), and the
#: turn may need a repair; these tests assert behaviour, not speed.
DEADLINE = 60.0


def test_openai_json_backend_against_llama_server(llama_server: str) -> None:
    model = parse_spec(f"openai-json:smollm2@{llama_server}").model
    assert isinstance(model, OpenAIModel)
    kb = scene_kb("kitchen")
    try:
        engine = DialogueEngine(kb, model, EngineConfig(deadline=DEADLINE))
        turn = engine.prepare(engine.ground(), "hello there", SPEAKER, (), None)
        schema = engine.schema_for(turn.context.snapshot, SPEAKER)
        raw = asyncio.run(model.chat(ChatRequest(engine.prompts.messages(turn.context), schema, turn.context), DEADLINE))
        parse_answer(raw.content)  # the server applied the schema's grammar: valid JSON answer
        snapshot, _ = engine.ground()
        started = time.monotonic()
        result = asyncio.run(engine.turn("go to the living room", speaker=SPEAKER))
        assert time.monotonic() - started < DEADLINE + 10.0  # generous: a busy machine
        assert result.backend in {model.name, "fallback"}
        assert_grounded(result, snapshot, SPEAKER, "go to the living room")
    finally:
        kb.close()
