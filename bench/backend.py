"""What an HTTP model backend adds to a turn, without the model: `situated bench backend`.

An instant OpenAI-compatible and Ollama server (uvicorn on loopback, a canned answer) and the real
`openai:` and `ollama:` backends. Measured per turn (median): the backend keeping its one client
(kept-alive connection), against the same backend closed after every turn, which makes a new
client (TLS context, connection) for each turn as the backends did before they kept one.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import time
from typing import Any

from fastapi import FastAPI

from api.server import serve_in_thread
from bench.progress import step
from dialogue.llm.base import ChatMessage, ChatModel, ChatRequest, TurnContext
from dialogue.llm.ollama import OllamaModel
from dialogue.llm.openai import OpenAIModel
from dialogue.reference.grounding import Snapshot

ANSWER = json.dumps({"verbal_ack": "OK", "user_intent": None})
REQUEST = ChatRequest((ChatMessage("user", "hello"),), {"type": "object"},
                      TurnContext("hello", "person_alice", Snapshot(revision=0, entities={})))


def instant_server() -> FastAPI:
    app = FastAPI()

    @app.post("/v1/chat/completions")
    async def openai_chat(payload: dict[str, Any]) -> dict[str, Any]:
        return {"choices": [{"index": 0, "finish_reason": "stop",
                             "message": {"role": "assistant", "content": ANSWER}}]}

    @app.post("/api/chat")
    async def ollama_chat(payload: dict[str, Any]) -> dict[str, Any]:
        return {"model": payload["model"], "created_at": "2026-01-01T00:00:00Z", "done": True,
                "done_reason": "stop", "message": {"role": "assistant", "content": ANSWER}}

    return app


async def turns(model: ChatModel, count: int, fresh: bool) -> float:
    """Median ms of `count` turns; `fresh`: the client closed after each (a new one per turn)."""
    times = []
    try:
        for _ in range(count):
            started = time.perf_counter()
            await model.chat(REQUEST, 5.0)
            if fresh:
                await model.aclose()
            times.append(time.perf_counter() - started)
    finally:
        await model.aclose()
    return statistics.median(times) * 1000


def run(count: int = 100) -> str:
    rows = []
    with serve_in_thread(instant_server()) as url:
        backends: dict[str, ChatModel] = {
            "openai": OpenAIModel("bench", f"{url}/v1"), "ollama": OllamaModel("bench", url)}
        for name, model in backends.items():
            step("backend", f"{name}: {count} turns with the kept client, {count} with a client per turn")
            kept = asyncio.run(turns(model, count, fresh=False))
            fresh = asyncio.run(turns(model, count, fresh=True))
            rows.append((name, kept, fresh))
    lines = ["HTTP backend overhead per turn, instant server on loopback (median ms)",
             f"  {'backend':10} {'kept client':>12} {'client per turn (before)':>26}"]
    lines += [f"  {name:10} {kept:12.2f} {fresh:26.2f}" for name, kept, fresh in rows]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="situated bench backend", description=__doc__)
    parser.add_argument("--turns", type=int, default=100, help="turns per measurement (default 100)")
    args = parser.parse_args(argv)
    if args.turns < 1:
        parser.error("--turns must be at least 1")
    print(run(args.turns))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
