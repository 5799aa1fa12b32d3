"""The web KB viewer: a static page (graph explorer, query box, fact editor, chat) at ``/`` and
``/viewer``, its assets under ``/viewer/assets/``. No build step, nothing fetched from elsewhere:
the page only talks to this service's own routes."""

from __future__ import annotations

from importlib.resources import files
from importlib.resources.abc import Traversable

from fastapi import APIRouter
from fastapi.responses import Response

from api.errors import ApiError

router = APIRouter(tags=["viewer"], include_in_schema=False)

MEDIA_TYPES = {
    ".html": "text/html; charset=utf-8",
    ".js": "text/javascript; charset=utf-8",
    ".css": "text/css; charset=utf-8",
    ".svg": "image/svg+xml",
}
# The page may only load from and connect to this service: a CDN reference would fail loudly
# instead of silently needing the network.
SECURITY_HEADERS = {
    "Content-Security-Policy": ("default-src 'self'; connect-src 'self'; img-src 'self' data:; "
                                "style-src 'self'; script-src 'self'; frame-ancestors 'none'"),
    "X-Content-Type-Options": "nosniff",
    "Cache-Control": "no-cache",
}


def _viewer_dir() -> Traversable:
    return files("api").joinpath("viewer")


def _asset(name: str) -> Response:
    suffix = "." + name.rsplit(".", 1)[-1] if "." in name else ""
    media = MEDIA_TYPES.get(suffix)
    source = _viewer_dir().joinpath(name)
    # Names are single file names of known kinds: no sub-paths, so nothing outside the folder.
    if media is None or "/" in name or "\\" in name or name.startswith(".") or not source.is_file():
        raise ApiError(404, "not_found", f"the viewer has no asset named {name!r}")
    return Response(source.read_bytes(), media_type=media, headers=SECURITY_HEADERS)


@router.get("/")
async def root() -> Response:
    """The viewer page."""
    return _asset("index.html")


@router.get("/viewer")
async def viewer() -> Response:
    """The viewer page (same as ``/``)."""
    return _asset("index.html")


@router.get("/viewer/assets/{name}")
async def asset(name: str) -> Response:
    """A script, style sheet or image of the viewer."""
    return _asset(name)
