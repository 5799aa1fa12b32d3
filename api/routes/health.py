"""Liveness and version."""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version
from typing import Any

from fastapi import APIRouter
from starlette.concurrency import run_in_threadpool

from api.deps import ServicesDep
from api.probe import probe
from kb import KB
from kb import __version__ as kb_version

router = APIRouter(tags=["service"])


def package_version() -> str:
    try:
        return version("situated")
    except PackageNotFoundError:
        return kb_version


def _kb_state(kb: KB) -> dict[str, Any]:
    with kb.lock:
        return {"revision": kb.revision, "size": kb.size(), "asserted": kb.size(inferred=False),
                "models": kb.models()}


@router.get("/health")
async def health(services: ServicesDep) -> dict[str, Any]:
    """KB size and revision, and whether the dialogue model backend is reachable."""
    state = await run_in_threadpool(_kb_state, services.kb)
    model = await probe(services.model)
    return {"status": "ok" if model["reachable"] else "degraded", "kb": state, "model": model,
            "events": {"subscribers": services.hub.listener_count}}


@router.get("/version")
async def version_info() -> dict[str, str]:
    return {"name": "situated", "version": package_version()}
