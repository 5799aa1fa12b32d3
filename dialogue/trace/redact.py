"""Traces with secrets taken out: the service's token (a person may say or paste it; a prompt may
quote it), `token=` URL parameters and the credentials of a URL (`https://user:key@host`).

>>> from dialogue.trace.record import TraceRecorder
>>> trace = TraceRecorder(input="my token is s3cret, see http://bob:pw@host/?token=abc").finish(
...     response="", backend="rules", answered_by="rules")
>>> redacted(trace, ["s3cret"]).input
'my token is [redacted], see http://[redacted]@host/?token=[redacted]'
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Sequence
from typing import Any

from dialogue.trace.record import TurnTrace

REDACTED = "[redacted]"
_TOKEN_PARAMETER = re.compile(r"([?&](?:access_)?token=)[^&\s\"]*", re.IGNORECASE)
_URL_CREDENTIALS = re.compile(r"(\b[a-z][a-z0-9+.-]*://)[^/@\s\"]+@", re.IGNORECASE)


def _clean(text: str, secrets: Sequence[str]) -> str:
    for secret in secrets:
        text = text.replace(secret, REDACTED)
    text = _TOKEN_PARAMETER.sub(rf"\g<1>{REDACTED}", text)
    return _URL_CREDENTIALS.sub(rf"\g<1>{REDACTED}@", text)


def _walk(value: Any, secrets: Sequence[str]) -> Any:
    """Every string value cleaned (keys are the trace's own field names, never secret)."""
    if isinstance(value, str):
        return _clean(value, secrets)
    if isinstance(value, dict):
        return {key: _walk(item, secrets) for key, item in value.items()}
    if isinstance(value, list):
        return [_walk(item, secrets) for item in value]
    return value


def redacted(trace: TurnTrace, secrets: Iterable[str]) -> TurnTrace:
    """A copy of `trace` in which no secret (nor URL token or credential) appears in any text."""
    kept = sorted({s for s in secrets if s}, key=len, reverse=True)  # a longer secret first
    return TurnTrace.model_validate(_walk(trace.model_dump(mode="json", by_alias=True), kept))
