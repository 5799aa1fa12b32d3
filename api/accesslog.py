"""Tokens kept out of the server's logs.

Clients that cannot set a header pass the service token in the URL (``?token=`` on the Rasa routes,
``?access_token=`` on event streams), and uvicorn logs every request line with its query string
(HTTP on ``uvicorn.access``, WebSocket handshakes on ``uvicorn.error``). A filter on both loggers
replaces those parameters' values before any handler formats the record.
"""

from __future__ import annotations

import copy
import logging
import re
from typing import Any

from uvicorn.config import LOGGING_CONFIG

REDACTED = "[redacted]"
_TOKEN_PARAMETER = re.compile(r"([?&](?:access_)?token=)[^&\s\"]*", re.IGNORECASE)
_LOGGERS = ("uvicorn.access", "uvicorn.error")


def redact(text: str) -> str:
    """``text`` with the value of every ``token=`` / ``access_token=`` URL parameter replaced."""
    return _TOKEN_PARAMETER.sub(rf"\g<1>{REDACTED}", text)


class RedactTokens(logging.Filter):
    def filter(self, record: logging.LogRecord) -> bool:
        if isinstance(record.msg, str):
            record.msg = redact(record.msg)
        if isinstance(record.args, tuple):
            record.args = tuple(redact(arg) if isinstance(arg, str) else arg for arg in record.args)
        return True


def log_config() -> dict[str, Any]:
    """uvicorn's logging configuration with ``RedactTokens`` on the loggers that print URLs."""
    config: dict[str, Any] = copy.deepcopy(LOGGING_CONFIG)
    config.setdefault("filters", {})["redact_tokens"] = {"()": RedactTokens}
    for name in _LOGGERS:
        config["loggers"].setdefault(name, {})["filters"] = ["redact_tokens"]
    return config
