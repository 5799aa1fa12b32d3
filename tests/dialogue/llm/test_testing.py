import asyncio

import pytest

from dialogue.llm.base import ChatRequest, ChatResult, ModelError
from dialogue.llm.testing import FunctionModel, ScriptedModel
from tests.dialogue.llm.common import ANSWER, request


def test_scripted_model_plays_its_queue_and_records_requests() -> None:
    model = ScriptedModel([ANSWER, {"verbal_ack": "hi", "user_intent": None}, ModelError("down")])
    req = request()
    assert asyncio.run(model.chat(req, 1)).content == ANSWER
    assert asyncio.run(model.chat(req, 1)).content == '{"verbal_ack": "hi", "user_intent": null}'
    with pytest.raises(ModelError, match="down"):
        asyncio.run(model.chat(req, 1))
    with pytest.raises(ModelError, match="no answer left"):
        asyncio.run(model.chat(req, 1))
    assert model.requests == [req] * 4


def test_function_model_sync_and_async() -> None:
    def echo(r: ChatRequest) -> str:
        return r.context.text

    async def later(r: ChatRequest) -> ChatResult:
        return ChatResult("x", "stop", understood=False)

    assert asyncio.run(FunctionModel(echo).chat(request(), 1)).content == "grab the cup"
    assert asyncio.run(FunctionModel(later).chat(request(), 1)).understood is False


def test_scripted_model_streams_its_answer_in_pieces() -> None:
    model = ScriptedModel([ANSWER, ModelError("down")], chunk_size=10)
    pieces: list[str] = []
    result = asyncio.run(model.chat_stream(request(), 1, pieces.append))
    assert result.content == ANSWER == "".join(pieces)
    assert [len(p) for p in pieces[:-1]] == [10] * (len(pieces) - 1) and len(pieces) == -(-len(ANSWER) // 10)
    with pytest.raises(ModelError, match="down"):
        asyncio.run(model.chat_stream(request(), 1, pieces.append))
    with pytest.raises(ValueError, match="chunk_size"):
        ScriptedModel(chunk_size=0)
