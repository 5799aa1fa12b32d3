"""Ollama backend: the official client, native `/api/chat`, `format` = the turn's JSON schema (D1, D16).

Temperature 0 and explicit `num_ctx`/`num_predict` (a silently truncated prompt or answer is the
classic failure); `done_reason` and empty content are checked; the timeout is the turn's time left.
One client per model, made on the first turn and kept (dialogue.llm.connection), closed by `aclose()`.
"""

from __future__ import annotations

import asyncio
from dataclasses import dataclass
from typing import Any

import httpx
import ollama

from dialogue.llm.base import ChatModel, ChatRequest, ChatResult, ModelError
from dialogue.llm.connection import LoopClient
from dialogue.trace.urlsecrets import redact

DEFAULT_HOST = "http://127.0.0.1:11434"


@dataclass(frozen=True)
class OllamaOptions:
    num_ctx: int = 4096
    num_predict: int = 256
    temperature: float = 0.0
    keep_alive: str = "30m"
    #: None leaves thinking to the model; some models (gpt-oss) refuse `False` (dialogue-compat §6.4).
    think: bool | str | None = False


class OllamaModel(ChatModel):
    """`transport` replaces httpx's network transport (tests: `httpx.MockTransport`)."""

    def __init__(
        self,
        model: str,
        host: str | None = None,
        options: OllamaOptions | None = None,
        *,
        transport: httpx.AsyncBaseTransport | None = None,
    ) -> None:
        if not model:
            raise ValueError("an Ollama model name is required, e.g. 'gemma3:1b'")
        self.model = model
        self.host = host or DEFAULT_HOST
        self.options = options or OllamaOptions()
        # No client-wide timeout: every call is bounded by the time its caller has left.
        self.client = LoopClient(
            lambda: ollama.AsyncClient(host=self.host, timeout=None, transport=transport), self.name
        )

    @property
    def name(self) -> str:
        return f"ollama:{self.model}@{redact(self.host)}"

    @property
    def setup_hint(self) -> str:
        return (f"start Ollama at {redact(self.host)} (ollama serve) and pull the model "
                f"(ollama pull {self.model}), or fix the URL in --llm")

    async def aclose(self) -> None:
        await self.client.aclose()

    async def probe(self, timeout: float) -> dict[str, Any]:
        """Lists the server's models: any answer but a server error means it is up."""
        url = redact(self.host.rstrip("/") + "/api/tags")
        try:
            async with asyncio.timeout(timeout):
                await self.client.get().list()
        except ollama.ResponseError as exc:
            status = exc.status_code
            return {"remote": True, "reachable": status < 500, "detail": f"{url}: HTTP {status}"}
        except (TimeoutError, ConnectionError, httpx.HTTPError) as exc:
            return {"remote": True, "reachable": False, "detail": f"{url}: {exc!r}"}
        except ValueError:  # an answer, but not a model list: something else listens there
            return {"remote": True, "reachable": True, "detail": f"{url}: not a model list"}
        return {"remote": True, "reachable": True, "detail": f"{url}: HTTP 200"}

    def payload(self, request: ChatRequest) -> dict[str, Any]:
        opts = self.options
        payload: dict[str, Any] = {
            "model": self.model,
            "messages": [m.as_dict() for m in request.messages],
            "format": request.schema,
            "options": {
                "temperature": opts.temperature,
                "num_ctx": opts.num_ctx,
                "num_predict": opts.num_predict,
            },
            "keep_alive": opts.keep_alive,
        }
        if opts.think is not None:
            payload["think"] = opts.think
        return payload

    async def preload(self, timeout: float = 60.0) -> None:
        """Load the model now (an empty chat), so the first turn does not pay a cold start (§6.4)."""
        client = self.client.get()
        try:
            async with asyncio.timeout(timeout):
                await client.chat(model=self.model, messages=[], keep_alive=self.options.keep_alive)
        except TimeoutError:
            raise ModelError(f"ollama did not load {self.model} within {timeout:.1f} s") from None
        except ollama.ResponseError as exc:
            message = f"ollama cannot load {self.model} (HTTP {exc.status_code}): {exc.error}"
            raise ModelError(message) from None
        except (ConnectionError, httpx.HTTPError) as exc:
            raise ModelError(f"ollama unreachable at {redact(self.host)}: {exc}") from None
        except ValueError as exc:  # the client parses the body: not JSON, or not a chat response
            raise ModelError(f"ollama at {redact(self.host)} answered a body that is not a chat "
                             "response") from exc

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult:
        payload = self.payload(request)
        client = self.client.get()
        try:
            async with asyncio.timeout(timeout):
                response = await client.chat(stream=False, **payload)
        except TimeoutError:
            raise ModelError(f"ollama did not answer within {timeout:.1f} s") from None
        except ollama.ResponseError as exc:
            raise ModelError(f"ollama error (HTTP {exc.status_code}): {exc.error}") from None
        except (ConnectionError, httpx.HTTPError) as exc:
            raise ModelError(f"ollama unreachable at {redact(self.host)}: {exc}") from None
        except ValueError as exc:  # the client parses the body: not JSON, or not a chat response
            raise ModelError(f"ollama at {redact(self.host)} answered a body that is not a chat response: "
                             f"{str(exc)[:200]}") from None
        content = response.message.content or ""
        reason = response.done_reason
        if reason == "length":
            raise ModelError(f"ollama answer truncated at num_predict={self.options.num_predict}")
        if not content.strip():
            raise ModelError(
                "ollama returned empty content (a thinking model may have answered in 'thinking')"
            )
        return ChatResult(content, reason, extra={"eval_count": response.eval_count})
