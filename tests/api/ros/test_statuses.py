"""/health's report as diagnostics statuses: levels and messages say what is wrong and where."""

from __future__ import annotations

from api.ros.statuses import ERROR, OK, WARN, statuses


def test_a_degraded_service_warns_with_its_reasons_each_part_at_its_level() -> None:
    report = {"status": "degraded", "reasons": ["storage: disk full", "model: ollama:x is not reachable (refused)"],
              "kb": {"revision": 7, "size": 10, "models": ["default", "alice"]},
              "model": {"name": "ollama:x", "remote": True, "reachable": False, "detail": "refused"},
              "events": {"subscribers": 2}, "intents": {"readers": 1, "last_seq": 99},
              "components": {"storage": {"ok": False, "code": "disk_full", "reason": "disk full"},
                             "expiry": {"ok": True}}}
    found = {s.name: s for s in statuses(report)}
    service = found["situated: service"]
    assert service.level == WARN and service.message == "storage: disk full; model: ollama:x is not reachable (refused)"
    assert dict(service.values)["intents last_seq"] == "99" and dict(service.values)["events subscribers"] == "2"
    assert found["situated: KB"].level == OK and dict(found["situated: KB"].values)["models"] == "default, alice"
    assert (found["situated: model"].level, found["situated: model"].message) == (
        ERROR, "ollama:x is not reachable (refused)")
    assert (found["situated: storage"].level, found["situated: storage"].message) == (WARN, "disk full")
    assert dict(found["situated: storage"].values) == {"code": "disk_full", "reason": "disk full"}
    assert found["situated: expiry"].level == OK


def test_a_kb_that_cannot_be_reached_is_an_error() -> None:
    report = {"status": "degraded", "reasons": ["store: timed out"], "components": {},
              "kb": {"role": "reader", "reachable": False, "error": "timed out"},
              "model": {"name": "rules", "reachable": True, "detail": "in-process"}}
    kb = next(s for s in statuses(report) if s.name == "situated: KB")
    assert (kb.level, kb.message) == (ERROR, "not reachable: timed out")
