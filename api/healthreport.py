"""What ``/health`` says: up or degraded, and, to a caller allowed to read, why.

Degraded when the model backend or the store is unreachable, or a registered component
(``Services.components``: the journal's storage, compaction, expiry, the store mirror...) is not
ok; each gives a reason. With ``allow_anonymous_reads=false`` an anonymous caller learns
only the status: model names, sizes and reasons are for callers with the token.
"""

from __future__ import annotations

from typing import Any

from starlette.concurrency import run_in_threadpool

from api.accesslog import redacted
from api.auth import authorise
from api.errors import ApiError
from api.probe import probe
from api.services import Services
from kb.errors import StoreUnavailable


def may_read_details(services: Services, presented: str | None) -> bool:
    try:
        authorise(services.settings, presented, write=False)
    except ApiError:
        return False
    return True


def _kb_state(services: Services) -> dict[str, Any]:
    summary = services.kb.summary()  # not the KB lock: /health answers while a query runs
    state: dict[str, Any] = {"revision": summary.revision, "size": summary.size,
                             "asserted": summary.asserted, "models": list(summary.models),
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


def _intents(services: Services) -> dict[str, Any]:
    """The stream's readers and last number; a reader's relay to the writer's stream instead."""
    if services.bus is not None:
        return {"readers": services.bus.reader_count, "last_seq": services.bus.last_seq}
    return {"relay": services.relay.report() if services.relay is not None else None}


async def health_report(services: Services, details: bool) -> dict[str, Any]:
    """``{"status"}``, and with ``details`` the KB, model, events, components and reasons."""
    state = await run_in_threadpool(_kb_health, services)
    model = await probe(services.model)
    components = await run_in_threadpool(services.components.report)
    reasons = [f"{name}: {status.reason}" for name, status in components.items() if not status.ok]
    if not model["reachable"]:
        reasons.append(f"model: {model['name']} is not reachable ({model['detail']})")
    if not state.get("reachable", True):
        reasons.append(f"store: {state.get('error', 'not reachable')}")
    status = "degraded" if reasons else "ok"
    if not details:
        return {"status": status}
    # No URL's credentials or secret parameters (a webhook's, the model server's, the store's).
    report: dict[str, Any] = redacted({
        "status": status, "reasons": reasons, "kb": state, "model": model,
        "events": {"subscribers": services.hub.listener_count}, "intents": _intents(services),
        "components": {name: s.as_dict() for name, s in components.items()}})
    return report
