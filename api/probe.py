"""Is the dialogue model backend reachable? A cheap request to the server a backend talks to.

In-process backends (rules, test models) are always reachable. A backend may also offer its own
``async ping(timeout) -> bool``, which is used when present, or a ``health() -> dict`` of its own
state (``reachable``, ``detail`` and whatever else it reports: the llama.cpp worker process's
crashes and restarts), which is merged in.
"""

from __future__ import annotations

from typing import Any

import httpx

from dialogue.llm.base import ChatModel
from dialogue.llm.ollama import OllamaModel
from dialogue.llm.openai import OpenAIModel


async def probe(model: ChatModel, timeout: float = 1.0) -> dict[str, Any]:
    """``{"name", "remote", "reachable", "detail"}`` for /health: of the model that reads prompts (the
    one behind the rules in a hybrid model)."""
    llm = model.llm
    if llm is None:
        return {"name": model.name, "remote": False, "reachable": True, "detail": "in-process"}
    model = llm
    ping = getattr(model, "ping", None)
    if callable(ping):
        return {"name": model.name, "remote": True, "reachable": bool(await ping(timeout)), "detail": ""}
    own_health = getattr(model, "health", None)
    if callable(own_health):
        return {"name": model.name, "remote": False, "reachable": True, "detail": "", **own_health()}
    if isinstance(model, OllamaModel):
        url = model.host.rstrip("/") + "/api/tags"
    elif isinstance(model, OpenAIModel):
        url = model.base_url + "/models"
    else:
        return {"name": model.name, "remote": False, "reachable": True, "detail": "in-process"}
    try:
        async with httpx.AsyncClient(timeout=timeout) as client:
            response = await client.get(url)
    except httpx.HTTPError as exc:
        return {"name": model.name, "remote": True, "reachable": False, "detail": f"{url}: {exc!r}"}
    reachable = response.status_code < 500
    return {"name": model.name, "remote": True, "reachable": reachable,
            "detail": f"{url}: HTTP {response.status_code}"}
