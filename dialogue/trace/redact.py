"""Traces with secrets taken out: the service's token (a person may say or paste it; a prompt may
quote it), secret URL parameters (`token=`, `key=`...) and the credentials of a URL
(`https://user:key@host`), as dialogue.trace.urlsecrets finds them (a model server's URL is in the
errors a trace records).

>>> from dialogue.trace.record import TraceRecorder
>>> trace = TraceRecorder(input="my token is s3cret, see http://bob:pw@host/?token=abc").finish(
...     response="", backend="rules", answered_by="rules")
>>> redacted(trace, ["s3cret"]).input
'my token is [redacted], see http://[redacted]@host/?token=[redacted]'
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

from dialogue.trace.record import TurnTrace
from dialogue.trace.urlsecrets import REDACTED, redact

__all__ = ["REDACTED", "redacted"]


def _clean(text: str, secrets: Sequence[str]) -> str:
    for secret in secrets:
        text = text.replace(secret, REDACTED)
    return redact(text)


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
