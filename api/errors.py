"""The one JSON error shape of every route: ``{"status", "code", "message", "details"}``.

Every failure goes through here: HTTP errors raised by the framework (404, 405), request
validation (422; 415 for a body sent without saying it is JSON), ``KbError`` and
``DialogueError`` (400; a failing model is 503), a query over the service's bounds (503
``query_timeout``, 413 ``too_many_rows`` or ``query_too_large``), a write whose TBox change is over
them (413 ``tbox_too_large``) or whose facts would cost the reasoner too much (413
``reasoning_too_large``), a full or failing data directory (507 ``storage_full``, 503
``storage_unavailable``), the service's own ``ApiError`` (auth, limits) and unexpected errors (500
with a generic message; the traceback goes to the log only).
"""

from __future__ import annotations

import logging
from collections.abc import Mapping
from http import HTTPStatus
from typing import Any

from fastapi import FastAPI, Request
from fastapi.encoders import jsonable_encoder
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse
from pydantic import BaseModel
from starlette.exceptions import HTTPException as StarletteHTTPException

from api.client import ClientError
from dialogue.errors import DialogueError
from dialogue.llm.base import ModelError
from dialogue.speakers import NotAPerson
from kb import KbError
from kb.errors import (
    ModelLimit,
    NotSerialisable,
    QueryTimeout,
    QueryTooLarge,
    ReasoningTooLarge,
    StorageError,
    StorageFull,
    StoreUnavailable,
    TBoxTooLarge,
    TooManyRows,
)

log = logging.getLogger("situated.api")

_CODES = {
    400: "bad_request",
    401: "unauthorized",
    403: "forbidden",
    404: "not_found",
    405: "method_not_allowed",
    406: "not_acceptable",
    413: "too_large",
    415: "unsupported_media_type",
    422: "invalid_request",
    429: "too_many_requests",
    500: "internal_error",
    503: "unavailable",
    507: "storage_full",
}


class ErrorBody(BaseModel):
    """What every error response carries."""

    status: int
    code: str
    message: str
    details: Any = None


class ApiError(StarletteHTTPException):
    """A failure the service reports as-is: status, a stable code, a message saying what is wrong.

    An HTTPException, so the framework lets it through where it wraps other errors (body reading).
    """

    def __init__(self, status: int, code: str, message: str, details: Any = None,
                 headers: dict[str, str] | None = None) -> None:
        super().__init__(status, message, headers)
        self.status = status
        self.code = code
        self.message = message
        self.details = details
        self.headers = headers


def error_body(status: int, code: str | None, message: str, details: Any = None) -> dict[str, Any]:
    body = ErrorBody(status=status, code=code or _CODES.get(status, "error"), message=message,
                     details=jsonable_encoder(details))
    return body.model_dump()


def error_response(status: int, code: str | None, message: str, details: Any = None,
                   headers: Mapping[str, str] | None = None) -> JSONResponse:
    return JSONResponse(error_body(status, code, message, details), status_code=status,
                        headers=dict(headers) if headers else None)


def _validation_details(exc: RequestValidationError) -> list[dict[str, Any]]:
    # The offending input is left out on purpose: it may be large or hold secrets.
    return [{"loc": list(e.get("loc", ())), "msg": e.get("msg", ""), "type": e.get("type", "")}
            for e in exc.errors()]


async def _api_error(request: Request, exc: Exception) -> JSONResponse:
    assert isinstance(exc, ApiError)
    return error_response(exc.status, exc.code, exc.message, exc.details, exc.headers)


async def _http_error(request: Request, exc: Exception) -> JSONResponse:
    assert isinstance(exc, StarletteHTTPException)
    status = exc.status_code
    message = exc.detail if isinstance(exc.detail, str) else HTTPStatus(status).phrase
    if status == 404 and message == "Not Found":
        message = f"no route for {request.method} {request.url.path}"
    elif status == 405:
        message = f"method {request.method} is not allowed on {request.url.path}"
    details = exc.detail if not isinstance(exc.detail, str) else None
    return error_response(status, None, message, details, getattr(exc, "headers", None))


def _not_json(request: Request, details: list[dict[str, Any]]) -> str | None:
    """Why a body that failed as a whole is no JSON to the route: it was sent without saying it is
    JSON (the framework then reads it as bytes, and the error would speak of a dictionary)."""
    media = request.headers.get("content-type", "").split(";")[0].strip().lower()
    json_sent = media == "application/json" or media.endswith("+json")
    if json_sent or not any(d["loc"] == ["body"] for d in details):
        return None
    said = f"is sent as {media}" if media else "has no Content-Type"
    return f"the request {said}; its body must be JSON: send Content-Type: application/json"


async def _validation_error(request: Request, exc: Exception) -> JSONResponse:
    assert isinstance(exc, RequestValidationError)
    details = _validation_details(exc)
    unsupported = _not_json(request, details)
    if unsupported is not None:
        return error_response(415, "unsupported_media_type", unsupported)
    first = details[0] if details else {"loc": [], "msg": "invalid request"}
    where = ".".join(str(p) for p in first["loc"]) or "request"
    return error_response(422, "invalid_request", f"{where}: {first['msg']}", details)


async def _client_error(request: Request, exc: Exception) -> JSONResponse:
    # A reader's write refused by the writer (or the writer unreachable): passed on unchanged.
    assert isinstance(exc, ClientError)
    return error_response(exc.status, exc.code, exc.message, exc.details)


async def _kb_error(request: Request, exc: Exception) -> JSONResponse:
    return error_response(400, "kb_error", str(exc))


async def _model_limit(request: Request, exc: Exception) -> JSONResponse:
    return error_response(413, "model_limit", f"{exc}")


async def _store_unavailable(request: Request, exc: Exception) -> JSONResponse:
    return error_response(503, "store_unavailable", str(exc))


def over_budget(exc: QueryTimeout | TooManyRows) -> ApiError:
    """A query or subscription past the service's limits: 413 ``too_many_rows`` or 503
    ``query_timeout`` (as other SPARQL servers answer a cancelled query; the service itself
    stays available)."""
    if isinstance(exc, TooManyRows):
        return ApiError(413, "too_many_rows", f"{exc} (the service's limit)", {"limit": exc.limit})
    return ApiError(503, "query_timeout", f"{exc} (the service's limit)", {"timeout": exc.seconds})


async def _over_budget(request: Request, exc: Exception) -> JSONResponse:
    assert isinstance(exc, QueryTimeout | TooManyRows)
    return await _api_error(request, over_budget(exc))


async def _query_too_large(request: Request, exc: Exception) -> JSONResponse:
    return error_response(413, "query_too_large", f"{exc} (the service's limit)")


async def _not_serialisable(request: Request, exc: Exception) -> JSONResponse:
    return error_response(406, "not_acceptable", str(exc))


async def _tbox_too_large(request: Request, exc: Exception) -> JSONResponse:
    return error_response(413, "tbox_too_large", f"{exc} (the service's limit)")


async def _reasoning_too_large(request: Request, exc: Exception) -> JSONResponse:
    return error_response(413, "reasoning_too_large", f"{exc} (the service's limit)")


async def _storage_full(request: Request, exc: Exception) -> JSONResponse:
    return error_response(507, "storage_full", str(exc))


async def _storage_error(request: Request, exc: Exception) -> JSONResponse:
    return error_response(503, "storage_unavailable", str(exc))


async def _dialogue_error(request: Request, exc: Exception) -> JSONResponse:
    return error_response(400, "dialogue_error", str(exc))


async def _not_a_person(request: Request, exc: Exception) -> JSONResponse:
    return error_response(400, "not_a_person", str(exc))


async def _model_error(request: Request, exc: Exception) -> JSONResponse:
    return error_response(503, "model_unavailable", str(exc))


async def _unexpected(request: Request, exc: Exception) -> JSONResponse:
    log.error("unhandled error on %s %s", request.method, request.url.path, exc_info=exc)
    # Starlette re-raises the error after this response, and the server then drops the
    # connection: saying so lets a keep-alive client open a new one instead of having its next
    # request reset.
    return error_response(500, "internal_error", "internal server error; see the service log",
                          headers={"Connection": "close"})


def install_error_handlers(app: FastAPI) -> None:
    app.add_exception_handler(ApiError, _api_error)
    app.add_exception_handler(StarletteHTTPException, _http_error)
    app.add_exception_handler(RequestValidationError, _validation_error)
    app.add_exception_handler(KbError, _kb_error)
    app.add_exception_handler(ClientError, _client_error)
    app.add_exception_handler(StoreUnavailable, _store_unavailable)
    app.add_exception_handler(ModelLimit, _model_limit)
    app.add_exception_handler(TooManyRows, _over_budget)
    app.add_exception_handler(QueryTimeout, _over_budget)
    app.add_exception_handler(QueryTooLarge, _query_too_large)
    app.add_exception_handler(TBoxTooLarge, _tbox_too_large)
    app.add_exception_handler(ReasoningTooLarge, _reasoning_too_large)
    app.add_exception_handler(NotSerialisable, _not_serialisable)
    app.add_exception_handler(StorageFull, _storage_full)  # before KbError's 400: more specific
    app.add_exception_handler(StorageError, _storage_error)
    app.add_exception_handler(DialogueError, _dialogue_error)
    app.add_exception_handler(ModelError, _model_error)  # more specific than DialogueError's 400
    app.add_exception_handler(NotAPerson, _not_a_person)
    app.add_exception_handler(Exception, _unexpected)
