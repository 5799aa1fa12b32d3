"""OpenAI-compatible backend (llama.cpp server, vLLM, OpenAI, Ollama's /v1) over httpx.

Only OpenAI fields are sent (D16): `response_format` in the variant the server accepts, with
explicit `temperature` and `max_tokens` (Ollama's /v1 forces 1.0 when they are absent). One client
per model, made on the first turn and kept (dialogue.llm.connection), closed by `aclose()`. The
base URL may carry a query (a server's `?key=`): the endpoints' paths are joined to its path, and
the URL is named with its secrets redacted (dialogue.trace.urlsecrets) in the name and every error.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any, Literal

import httpx

from dialogue.llm.base import ChatModel, ChatRequest, ChatResult, ModelError
from dialogue.llm.connection import LoopClient
from dialogue.trace.urlsecrets import redact

ResponseFormat = Literal["json_schema", "json_object"]
DEFAULT_BASE_URL = "http://127.0.0.1:8080/v1"


@dataclass(frozen=True)
class OpenAIOptions:
    response_format: ResponseFormat = "json_schema"
    temperature: float = 0.0
    max_tokens: int = 256
    api_key_env: str = "OPENAI_API_KEY"


class OpenAIModel(ChatModel):
    """`transport` replaces httpx's network transport (tests: `httpx.MockTransport`)."""

    def __init__(
        self,
        model: str,
        base_url: str | None = None,
        options: OpenAIOptions | None = None,
        *,
        transport: httpx.AsyncBaseTransport | None = None,
    ) -> None:
        if not model:
            raise ValueError("an OpenAI-compatible model name is required")
        self.model = model
        self.base_url = (base_url or DEFAULT_BASE_URL).rstrip("/")
        self.options = options or OpenAIOptions()
        self.client = LoopClient(lambda: httpx.AsyncClient(transport=transport), self.name)

    @property
    def name(self) -> str:
        return f"openai:{self.model}@{redact(self.base_url)}"

    @property
    def setup_hint(self) -> str:
        return (f"start the OpenAI-compatible server at {redact(self.base_url)} serving {self.model!r}, "
                "or fix the model name or URL in --llm")

    async def aclose(self) -> None:
        await self.client.aclose()

    def _endpoint(self, path: str) -> tuple[httpx.URL, str]:
        """The URL of ``path`` under the base URL (its query kept), and how it is named."""
        base = httpx.URL(self.base_url)
        url = base.copy_with(path=base.path.rstrip("/") + path)
        return url, redact(str(url))

    def _headers(self) -> dict[str, str]:
        key = os.environ.get(self.options.api_key_env)
        return {"Authorization": f"Bearer {key}"} if key else {}

    async def probe(self, timeout: float) -> dict[str, Any]:
        """Lists the server's models: any answer but a server error means it is up."""
        url, shown = self._endpoint("/models")
        try:
            response = await self.client.get().get(url, headers=self._headers(), timeout=timeout)
        except httpx.HTTPError as exc:
            return {"remote": True, "reachable": False, "detail": redact(f"{shown}: {exc!r}")}
        return {"remote": True, "reachable": response.status_code < 500,
                "detail": f"{shown}: HTTP {response.status_code}"}

    def payload(self, request: ChatRequest) -> dict[str, Any]:
        opts = self.options
        response_format: dict[str, Any]
        if opts.response_format == "json_schema":
            # `name` is required by vLLM and OpenAI, ignored by Ollama and llama.cpp: portable.
            response_format = {
                "type": "json_schema",
                "json_schema": {"name": "chatbot_response", "schema": request.schema},
            }
        else:
            response_format = {"type": "json_object", "schema": request.schema}
        return {
            "model": self.model,
            "messages": [m.as_dict() for m in request.messages],
            "response_format": response_format,
            "temperature": opts.temperature,
            "max_tokens": opts.max_tokens,
            "stream": False,
        }

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult:
        headers = self._headers()
        url, shown = self._endpoint("/chat/completions")
        try:
            response = await self.client.get().post(
                url, json=self.payload(request), headers=headers, timeout=timeout
            )
        except httpx.TimeoutException:
            raise ModelError(f"{shown} did not answer within {timeout:.1f} s") from None
        except httpx.HTTPError as exc:
            raise ModelError(redact(f"{shown} unreachable: {exc}")) from None
        if response.status_code != 200:
            raise ModelError(f"{shown} answered HTTP {response.status_code}: {response.text[:200]}")
        try:
            body = response.json()
            choice = body["choices"][0]
            content = choice["message"].get("content") or ""
            reason = choice.get("finish_reason")
        except (ValueError, KeyError, IndexError, TypeError, AttributeError):
            raise ModelError(f"{shown} answered an unexpected body: {response.text[:200]}") from None
        if reason == "length":
            raise ModelError(f"answer truncated at max_tokens={self.options.max_tokens}")
        if not isinstance(content, str) or not content.strip():
            raise ModelError("the server returned empty content")
        return ChatResult(content, reason)
