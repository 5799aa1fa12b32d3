"""Bearer-token access control: writes need the token when one is configured; reads too unless
``allow_anonymous_reads``. Tokens are compared in constant time."""

from __future__ import annotations

import hmac

from fastapi.security import HTTPBearer

from api.errors import ApiError
from api.settings import Settings

bearer = HTTPBearer(auto_error=False, description="the service token (settings.token)")


def token_from_header(value: str | None) -> str | None:
    """The token of an ``Authorization: Bearer <token>`` header value, else None."""
    if not value:
        return None
    scheme, _, token = value.partition(" ")
    return token.strip() or None if scheme.lower() == "bearer" else None


def authorise(settings: Settings, presented: str | None, write: bool) -> None:
    """Raise 401 (no token) or 403 (wrong token) unless the caller may do this."""
    if settings.token is None or (not write and settings.allow_anonymous_reads):
        return
    if presented is None:
        raise ApiError(401, "unauthorized", "this request needs 'Authorization: Bearer <token>'",
                       headers={"WWW-Authenticate": "Bearer"})
    expected = settings.token.get_secret_value().encode()
    if not hmac.compare_digest(presented.encode(), expected):
        raise ApiError(403, "forbidden", "the bearer token is not valid for this service")
