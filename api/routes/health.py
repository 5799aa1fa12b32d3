"""Liveness and version."""

from __future__ import annotations

from dataclasses import asdict
from importlib.metadata import PackageNotFoundError, version
from typing import Any

from fastapi import APIRouter
from starlette.concurrency import run_in_threadpool

from api.deps import ServicesDep
from api.probe import probe
from api.services import Services
from kb import __version__ as kb_version
from kb.endpoint import StoreUnavailable

router = APIRouter(tags=["service"])


def package_version() -> str:
    try:
        return version("situated")
    except PackageNotFoundError:
        return kb_version


def _kb_state(services: Services) -> dict[str, Any]:
    kb = services.kb
    with kb.lock:
        state: dict[str, Any] = {"revision": kb.revision, "size": kb.size(),
                                 "asserted": kb.size(inferred=False), "models": kb.models(),
                                 "role": services.settings.role}
    if services.store is not None:
        state["store"] = services.store.endpoint.spec.query_url
        if services.store.mirror is not None:
            state["store_in_sync"] = not services.store.mirror.stale
    return state


def _kb_health(services: Services) -> dict[str, Any]:
    try:
        return _kb_state(services)
    except StoreUnavailable as exc:
        return {"role": services.settings.role, "reachable": False, "error": str(exc)}


@router.get("/health")
async def health(services: ServicesDep) -> dict[str, Any]:
    """KB size, revision and role (standalone, or the writer or a reader of a shared store),
    and whether the dialogue model backend and the store are reachable."""
    state = await run_in_threadpool(_kb_health, services)
    model = await probe(services.model)
    components = services.components()
    healthy = (model["reachable"] and state.get("reachable", True) and state.get("store_in_sync", True)
               and all(c.ok for c in components.values()))
    return {"status": "ok" if healthy else "degraded", "kb": state, "model": model,
            "events": {"subscribers": services.hub.listener_count},
            "components": {name: asdict(c) for name, c in components.items()}}


@router.get("/version")
async def version_info() -> dict[str, str]:
    return {"name": "situated", "version": package_version()}
