"""Liveness and version."""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version
from typing import Any

from fastapi import APIRouter

from api.deps import PresentedToken, ServicesDep
from api.healthreport import health_report, may_read_details
from kb import __version__ as kb_version

router = APIRouter(tags=["service"])


def package_version() -> str:
    try:
        return version("situated")
    except PackageNotFoundError:
        return kb_version


@router.get("/health")
async def health(services: ServicesDep, token: PresentedToken) -> dict[str, Any]:
    """``ok`` or ``degraded``, to anyone (a monitor needs no token); to callers allowed to read,
    also why (``reasons``), the KB's size, revision and role, the model backend, the store, and each
    component (storage, compaction)."""
    return await health_report(services, may_read_details(services, token))


@router.get("/version")
async def version_info() -> dict[str, str]:
    return {"name": "situated", "version": package_version()}
