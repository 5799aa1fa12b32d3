"""/health: ok or degraded with the reasons, from the model, the store and every registered
component; with closed reads, an anonymous caller learns only up or down."""

from __future__ import annotations

from collections.abc import Callable

import httpx
from pydantic import SecretStr

from api.settings import Settings
from kb import KB
from kb.status import StatusCell
from tests.api.conftest import SCENE, Live
from tests.kb.test_summary import lock_held_elsewhere

TOKEN = "health-token"


def test_anonymous_health_with_closed_reads_says_only_up_or_down(live_factory: Callable[..., Live]) -> None:
    live = live_factory(Settings(scene=SCENE, token=SecretStr(TOKEN), allow_anonymous_reads=False))
    cell = StatusCell()
    live.services.components.register("worker", cell.get)
    for headers in ({}, {"authorization": "Bearer wrong"}):
        answer = live.client.get("/health", headers=headers)
        assert answer.status_code == 200 and answer.json() == {"status": "ok"}
    cell.failed("worker_down", "the worker at model.gguf stopped")
    assert live.client.get("/health").json() == {"status": "degraded"}  # no names, no reasons
    full = live.client.get("/health", headers={"authorization": f"Bearer {TOKEN}"}).json()
    assert full["status"] == "degraded" and full["model"]["name"] and full["kb"]["revision"] >= 0
    assert full["reasons"] == ["worker: the worker at model.gguf stopped"]


def test_open_reads_give_everyone_the_full_health(live_factory: Callable[..., Live]) -> None:
    live = live_factory(Settings(scene=SCENE, token=SecretStr(TOKEN)))
    health = live.client.get("/health").json()
    assert health["status"] == "ok" and health["reasons"] == [] and "model" in health


def test_a_failing_component_degrades_health_until_it_recovers(live_factory: Callable[..., Live]) -> None:
    live = live_factory()
    cell = StatusCell()
    live.services.components.register("mirror", cell.get)
    assert live.client.get("/health").json()["components"]["mirror"] == {"ok": True}
    cell.failed("store_unavailable", "the store refused the update", retry_in=2.0)
    cell.failed("store_unavailable", "the store refused the update", retry_in=4.0)
    health = live.client.get("/health").json()
    assert health["status"] == "degraded" and health["reasons"] == ["mirror: the store refused the update"]
    mirror = health["components"]["mirror"]
    assert mirror["ok"] is False and mirror["code"] == "store_unavailable" and mirror["failures"] == 2
    assert mirror["retry_in"] == 4.0 and mirror["since"] > 0
    cell.succeeded()
    assert live.client.get("/health").json()["status"] == "ok"


def test_health_answers_while_a_read_holds_the_kb(live_factory: Callable[..., Live]) -> None:
    with KB() as kb:
        kb.add(["cup_1 isOn table_1"])
        live = live_factory(Settings(scene=SCENE), kb=kb)
        revision = kb.revision
        with lock_held_elsewhere(kb), httpx.Client(base_url=live.url, timeout=10.0) as http:
            health = http.get("/health")  # waited for the lock (here: forever) before
        assert health.status_code == 200
        assert health.json()["kb"] | {"size": 0, "asserted": 0} == {
            "revision": revision, "size": 0, "asserted": 0, "models": ["default"], "role": "standalone"}
