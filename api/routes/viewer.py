"""The web KB viewer: a static page (graph explorer, query box, fact editor, chat) at ``/`` and
``/viewer``, its assets under ``/viewer/assets/`` (Starlette's ``StaticFiles`` over the package's
``api/viewer`` folder). No build step, nothing fetched from elsewhere: the page only talks to this
service's own routes."""

from __future__ import annotations

from importlib.resources import files
from typing import Any

from fastapi import APIRouter
from fastapi.responses import Response
from starlette.staticfiles import StaticFiles

router = APIRouter(tags=["viewer"], include_in_schema=False)

#: Where the assets are mounted (``api.app`` mounts ``assets()`` there).
ASSETS_PATH = "/viewer/assets"
# The page may only load from and connect to this service: a CDN reference would fail loudly
# instead of silently needing the network.
SECURITY_HEADERS = {
    "Content-Security-Policy": ("default-src 'self'; connect-src 'self'; img-src 'self' data:; "
                                "style-src 'self'; script-src 'self'; frame-ancestors 'none'"),
    "X-Content-Type-Options": "nosniff",
    "Cache-Control": "no-cache",
}


class ViewerFiles(StaticFiles):
    """The viewer's files, each with the headers that keep the page on this service. A name that
    is not a file of the folder is 404 in the service's error shape (HTTPException)."""

    def file_response(self, *args: Any, **kwargs: Any) -> Response:
        response = super().file_response(*args, **kwargs)
        response.headers.update(SECURITY_HEADERS)
        return response


def assets() -> ViewerFiles:
    return ViewerFiles(packages=[("api", "viewer")])


def _page() -> Response:
    page = files("api").joinpath("viewer", "index.html")
    return Response(page.read_bytes(), media_type="text/html; charset=utf-8", headers=SECURITY_HEADERS)


@router.get("/")
async def root() -> Response:
    """The viewer page."""
    return _page()


@router.get("/viewer")
async def viewer() -> Response:
    """The viewer page (same as ``/``)."""
    return _page()
