"""Secrets in URLs are replaced wherever a URL is shown: by the names services give secret
parameters, the credentials of a URL, and (for webhooks) the path (red team round 3 rerun: a
webhook's `auth_token=`, `client_secret=`, `x-api-key=`, `access-token=` and Slack path once
appeared in anonymous /health and the log)."""

from __future__ import annotations

import pytest

from dialogue.trace.urlsecrets import REDACTED, hide_path, redact


@pytest.mark.parametrize("name", ["token", "access_token", "access-token", "auth_token", "private_token", "key",
                                  "api_key", "apiKey", "x-api-key", "client_secret", "password", "passwd", "pwd",
                                  "sig", "signature", "auth", "credential", "session_id", "TOKEN"])
def test_every_secret_parameter_is_redacted_and_the_rest_kept(name: str) -> None:
    shown = redact(f"at http://host:1/h?room=4&{name}=s3cr3t&lang=en, then")
    assert shown == f"at http://host:1/h?room=4&{name}={REDACTED}&lang=en, then"


def test_credentials_are_redacted_in_any_scheme() -> None:
    assert redact("https://bob:p%40ss@host/x and ws://tok@h:2") == (
        f"https://{REDACTED}@host/x and ws://{REDACTED}@h:2")
    assert redact("openai:gpt@http://h/v1") == "openai:gpt@http://h/v1"  # a model spec's @ is no credential


def test_a_redacted_value_ends_where_the_text_around_it_goes_on() -> None:
    assert redact("(model: m@http://h/v1?key=k3y; scene: demo)") == f"(model: m@http://h/v1?key={REDACTED}; scene: demo)"


@pytest.mark.parametrize(("url", "shown"), [
    ("https://hooks.slack.com/services/T000/B000/XXXX", f"https://hooks.slack.com/{REDACTED}"),
    ("http://u:p@127.0.0.1:8080/api/webhooks/1/abc?token=t&room=4",
     f"http://127.0.0.1:8080/{REDACTED}?token={REDACTED}&room=4"),
    ("http://[::1]:9000/", "http://[::1]:9000/"),
    ("http://host", "http://host"),
    ("http://host:notaport/x", REDACTED),
])
def test_hide_path_keeps_only_where_the_url_goes(url: str, shown: str) -> None:
    assert hide_path(url) == shown
