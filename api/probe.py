"""Is the dialogue model backend reachable? Asked of the model that reads prompts (the one behind
the rules in a hybrid model): a remote backend sends one cheap request to its server, an in-process
one reports its own state (the llama.cpp worker process's crashes and restarts)."""

from __future__ import annotations

from typing import Any

from dialogue.llm.base import ChatModel


async def probe(model: ChatModel, timeout: float = 1.0) -> dict[str, Any]:
    """``{"name", "remote", "reachable", "detail"}`` (and the backend's own extras) for /health."""
    target = model.llm or model
    return {"name": target.name, **await target.probe(timeout)}
