"""Secrets a URL may carry, replaced wherever the service shows or logs a URL.

A webhook's ``https://user:pass@host/hook?token=...``, a model server's ``?key=...``: the values of
URL parameters named as services name secrets (any name holding ``token``, ``key``, ``secret``,
``pass``, ``pwd``, ``sig``, ``auth``, ``credential`` or ``session``: ``auth_token``, ``client_secret``,
``x-api-key``, ``apiKey``...) and a URL's credentials. Some receivers put the secret in the path
instead (Slack's ``/services/T.../B.../XXXX``, Discord's ``/api/webhooks/ID/TOKEN``), which no
pattern can tell from a plain path: ``hide_path`` shows such a URL without its path.

>>> redact("see http://bob:pw@host/v1?model=m&x-api-key=abc&apiKey=def")
'see http://[redacted]@host/v1?model=m&x-api-key=[redacted]&apiKey=[redacted]'
>>> hide_path("https://bob:pw@hooks.example.org:8443/services/T0/B0/XYZ?token=abc&room=4")
'https://hooks.example.org:8443/[redacted]?token=[redacted]&room=4'
"""

from __future__ import annotations

import re
from urllib.parse import urlsplit

REDACTED = "[redacted]"
_SECRET_PARAMETER = re.compile(
    r"([?&;][^=&#\s\"'?]*(?:token|key|secret|pass|pwd|sig|auth|credential|session)[^=&#\s\"'?]*=)"
    r"[^&#;\s\"']*", re.IGNORECASE)
_URL_CREDENTIALS = re.compile(r"(\b[a-z][a-z0-9+.-]*://)[^/?#@\s\"']+@", re.IGNORECASE)


def redact(text: str) -> str:
    """``text`` with the value of every secret URL parameter and every URL's credentials
    (``user:pass@``) replaced."""
    return _URL_CREDENTIALS.sub(rf"\g<1>{REDACTED}@", _SECRET_PARAMETER.sub(rf"\g<1>{REDACTED}", text))


def hide_path(url: str) -> str:
    """``url`` without its credentials and with its path as ``/[redacted]`` (its query redacted)."""
    try:
        parts = urlsplit(url)
        host = parts.hostname or ""
        port = parts.port
    except ValueError:  # not a URL: nothing of it is shown
        return REDACTED
    host = f"[{host}]" if ":" in host else host
    shown = f"{parts.scheme}://{host}" + (f":{port}" if port is not None else "")
    shown += f"/{REDACTED}" if parts.path.strip("/") else parts.path
    return shown + (redact(f"?{parts.query}") if parts.query else "")
