"""No secret in a trace that is read: the token, URL tokens and credentials, in every text."""

from __future__ import annotations

from dialogue.trace.record import TraceRecorder
from dialogue.trace.redact import REDACTED, redacted


def test_every_text_is_cleaned_and_the_rest_kept() -> None:
    recorder = TraceRecorder(input="the token is tok-123")
    exchange = recorder.request("openai:m@http://user:pw@host:1", [("user", 'say "tok-123"')],
                                {"enum": ["tok-123", "cup_1"]})
    recorder.answered(exchange, '{"verbal_ack": "tok-123 ?token=abc"}', "stop", 0.0)
    trace = recorder.finish(response="ok tok-123", backend="rules", answered_by="rules")
    clean = redacted(trace, ["tok-123", ""])
    text = clean.model_dump_json(by_alias=True)
    assert "tok-123" not in text and "pw@" not in text and "token=abc" not in text
    assert clean.input == f"the token is {REDACTED}" and clean.exchanges[0].json_schema["enum"][1] == "cup_1"
    assert clean.exchanges[0].model == f"openai:m@http://{REDACTED}@host:1"
    assert redacted(trace, []).input == "the token is tok-123"  # no token configured: nothing to hide


def test_a_model_servers_key_is_cleaned_from_the_errors_a_trace_records() -> None:
    """Red team round 3 rerun: `GET /dialogues/{id}/turns` (an anonymous read) once showed the
    `?key=` and `api_key=` of the model server's URL in a failed turn's error."""
    recorder = TraceRecorder(input="hello")
    exchange = recorder.request("openai:m@http://host:1/v1?key=k3y", [("user", "hello")], {})
    recorder.answered(exchange, None, None, 0.0,
                      error="http://host:1/v1/chat/completions?key=k3y&api_key=k4y answered HTTP 500")
    trace = recorder.finish(response="Sorry", backend="fallback", answered_by=None,
                            error_msg="openai:m@http://host:1/v1?x-api-key=k5y: unreachable")
    text = redacted(trace, []).model_dump_json(by_alias=True)
    assert not [secret for secret in ("k3y", "k4y", "k5y") if secret in text], text
    assert f"x-api-key={REDACTED}" in text and f"api_key={REDACTED}" in text
