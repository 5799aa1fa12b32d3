"""Secrets kept out of the server's logs and of what /health says.

Clients that cannot set a header pass the service token in the URL (``?token=`` on the Rasa routes,
``?access_token=`` on event streams), and uvicorn logs every request line with its query string
(HTTP on ``uvicorn.access``, WebSocket handshakes on ``uvicorn.error``). The service's own
outgoing URLs may hold secrets too: a webhook's ``https://user:pass@host/?token=...``, a model
server's ``?key=...``, which httpx logs with every request (``httpx``). A filter on those loggers
replaces the values of such parameters, and a URL's credentials, before any handler formats the
record; ``redact`` (dialogue.trace.urlsecrets) does the same for text the service shows (/health's reasons
and names). httpx's line per request is not logged at all (only its warnings): a webhook's URL may
hold its secret in the path, which no filter can tell (the couriers name their URL without it).
"""

from __future__ import annotations

import copy
import logging
from typing import Any

import httpx
from uvicorn.config import LOGGING_CONFIG

from dialogue.trace.urlsecrets import REDACTED, redact

__all__ = ["REDACTED", "RedactTokens", "log_config", "redact", "redact_client_logs", "redacted"]
_LOGGERS = ("uvicorn.access", "uvicorn.error", "httpx")


def redacted(value: Any) -> Any:
    """``value`` (JSON-like) with ``redact`` applied to every string in it."""
    if isinstance(value, str):
        return redact(value)
    if isinstance(value, dict):
        return {key: redacted(item) for key, item in value.items()}
    if isinstance(value, list):
        return [redacted(item) for item in value]
    return value


class RedactTokens(logging.Filter):
    def filter(self, record: logging.LogRecord) -> bool:
        if isinstance(record.msg, str):
            record.msg = redact(record.msg)
        if isinstance(record.args, tuple):
            # httpx passes its URL as an httpx.URL: redacted as text
            record.args = tuple(redact(str(arg)) if isinstance(arg, str | httpx.URL) else arg
                                for arg in record.args)
        return True


def redact_client_logs() -> None:
    """Put ``RedactTokens`` on the logger of the service's HTTP client (httpx), once: it logs
    every request's URL, a webhook's or a model server's with its secrets; and keep only its
    warnings (its request lines name a webhook's path, which may be its secret)."""
    logger = logging.getLogger("httpx")
    logger.setLevel(logging.WARNING)
    if not any(isinstance(f, RedactTokens) for f in logger.filters):
        logger.addFilter(RedactTokens())


def log_config() -> dict[str, Any]:
    """uvicorn's logging configuration with ``RedactTokens`` on the loggers that print URLs."""
    config: dict[str, Any] = copy.deepcopy(LOGGING_CONFIG)
    config.setdefault("filters", {})["redact_tokens"] = {"()": RedactTokens}
    for name in _LOGGERS:
        config["loggers"].setdefault(name, {})["filters"] = ["redact_tokens"]
    config["loggers"]["httpx"]["level"] = "WARNING"
    return config
