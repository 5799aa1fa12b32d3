"""Invalid Unicode refused at the edge, as a small ASGI middleware: 400 ``invalid_unicode``.

A lone surrogate (JSON's ``"\\ud800"``, or UTF-8 bytes that encode one) is a Python string but no
UTF-8 document: once stored it breaks every answer that names it. So before any route runs, the
path and query string must percent-decode to UTF-8, and a request body must be UTF-8 (a form's
fields after percent-decoding) with no JSON escape of a lone surrogate. XML bodies (RDF/XML, TriX,
SVG) declare their own encoding and XML cannot express a surrogate, so they are left to their
parsers. The KB refuses such text too (kb.unicode), for what escapes inside a document produce
(``"\\ud800"`` in Turtle, SPARQL or a statement) and for library users.
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable
from urllib.parse import unquote_to_bytes

from api.errors import ApiError, error_body
from api.limits import ASGIApp, Message, Receive, Scope, Send

_JSON_ESCAPE = re.compile(r"\\(?:u([0-9a-fA-F]{4})|.)", re.DOTALL)
_HIGH = range(0xD800, 0xDC00)
_LOW = range(0xDC00, 0xE000)


def invalid_unicode(message: str) -> ApiError:
    return ApiError(400, "invalid_unicode", message)


def _utf8(data: bytes, what: str) -> str:
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise invalid_unicode(f"{what} is not valid UTF-8: byte {exc.start} "
                              f"(0x{data[exc.start]:02X}) {exc.reason}") from None


def _url_encoded(data: bytes, what: str) -> None:
    """Each field of a query string or form must percent-decode to UTF-8."""
    for field in data.split(b"&"):
        _utf8(unquote_to_bytes(field.replace(b"+", b" ")), what)


def _lone_surrogate_escape(text: str) -> int | None:
    """Where JSON text escapes a lone surrogate (``\\ud800`` not followed by ``\\udc00``-``\\udfff``,
    or a low one alone), else None. Escapes are read left to right, so ``\\\\ud800`` is text."""
    high_at = high_end = -1
    for match in _JSON_ESCAPE.finditer(text):
        code = int(match.group(1), 16) if match.group(1) else None
        if high_at >= 0:
            if match.start() != high_end or code not in _LOW:
                return high_at
            high_at = -1
        elif code in _HIGH:
            high_at, high_end = match.start(), match.end()
        elif code in _LOW:
            return match.start()
    return high_at if high_at >= 0 else None


def _check_json(body: bytes) -> None:
    text = _utf8(body, "the request body")
    at = _lone_surrogate_escape(text) if "\\u" in text else None
    if at is not None:
        raise invalid_unicode(f"the JSON body is not valid Unicode: {text[at:at + 6]} at character {at} "
                              "is a lone surrogate (a surrogate escape needs its pair)")


def _check_form(body: bytes) -> None:
    _url_encoded(body, "a form field of the request body")


def _check_text(body: bytes) -> None:
    _utf8(body, "the request body")


def _body_check(content_type: str) -> Callable[[bytes], None] | None:
    media = content_type.split(";", 1)[0].strip().lower()
    if not media or media == "application/json" or media.endswith("+json"):
        return _check_json  # FastAPI reads a body without a Content-Type as JSON
    subtype = media.rpartition("/")[2]
    if subtype in ("xml", "trix") or subtype.endswith("+xml"):
        return None
    return _BODY_CHECKS.get(media, _check_text)


_BODY_CHECKS: dict[str, Callable[[bytes], None]] = {"application/x-www-form-urlencoded": _check_form}


class ValidText:
    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] not in ("http", "websocket"):
            await self.app(scope, receive, send)
            return
        try:
            _url_encoded(scope.get("raw_path") or scope["path"].encode(), "the request path")
            _url_encoded(scope.get("query_string", b""), "the query string")
        except ApiError as exc:
            await _refuse(scope, send, exc)
            return
        check = _body_check(_header(scope, b"content-type")) if _has_body(scope) else None
        if check is None:
            await self.app(scope, receive, send)
            return
        try:
            body = await _read_body(receive)
            check(body)
        except ApiError as exc:  # this one, or the body-size limit's 413
            await _refuse(scope, send, exc)
            return
        await self.app(scope, _replay(body, receive), send)


def _header(scope: Scope, name: bytes) -> str:
    for key, value in scope.get("headers", ()):
        if key == name:
            return bytes(value).decode("latin-1")
    return ""


def _has_body(scope: Scope) -> bool:
    if scope["type"] != "http":
        return False
    length = _header(scope, b"content-length").strip()
    return (length not in ("", "0")) or bool(_header(scope, b"transfer-encoding"))


async def _read_body(receive: Receive) -> bytes:
    chunks: list[bytes] = []
    while True:
        message = await receive()
        if message["type"] != "http.request":
            break
        chunks.append(message.get("body", b""))
        if not message.get("more_body", False):
            break
    return b"".join(chunks)


def _replay(body: bytes, receive: Receive) -> Receive:
    """The body already read, as one message; then the client's own messages (disconnect)."""
    pending = [{"type": "http.request", "body": body, "more_body": False}]

    async def replayed() -> Message:
        return pending.pop() if pending else await receive()

    return replayed


async def _refuse(scope: Scope, send: Send, error: ApiError) -> None:
    if scope["type"] == "websocket":
        await send({"type": "websocket.close", "code": 1007, "reason": error.message[:120]})
        return
    payload = json.dumps(error_body(error.status, error.code, error.message, error.details)).encode()
    headers = [(b"content-type", b"application/json"), (b"content-length", str(len(payload)).encode())]
    if error.status == 413:
        headers.append((b"connection", b"close"))  # the rest of the body was not read
    await send({"type": "http.response.start", "status": error.status, "headers": headers})
    await send({"type": "http.response.body", "body": payload})
