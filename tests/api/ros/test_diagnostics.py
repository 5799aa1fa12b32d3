"""/diagnostics on a real graph: the service's health (service, KB, model, components) every
diagnostics_period, as /health reports it; a model that does not answer is an error and the service
warns, saying why."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from tests.api.ros.conftest import Probe, RosNode
from tests.waiting import until

ARRAY = "diagnostic_msgs/msg/DiagnosticArray"
OK, WARN, ERROR = 0, 1, 2


def statuses(probe: Probe, count: int = 1) -> dict[str, dict[str, Any]]:
    last = probe.messages("/diagnostics", count=count)[-1]
    return {s["name"]: {**s, "level": s["level"][0], "values": {v["key"]: v["value"] for v in s["values"]}}
            for s in last["status"]}


def test_the_services_health_is_on_diagnostics(ros_node: RosNode, probe: Probe) -> None:
    probe("subscribe", topic="/diagnostics", type=ARRAY)
    found = statuses(probe)
    assert {"situated: service", "situated: KB", "situated: model", "situated: expiry"} <= set(found)
    assert all(s["level"] == OK and s["hardware_id"] == "situated" for s in found.values())
    assert found["situated: service"]["values"]["Module name"] == "situated"
    assert found["situated: model"]["message"] == "rules: in-process"
    probe.call("/kb/revise", "kb_msgs/srv/Revise", method="update", statements=["lamp_1 isOn desk_1"])
    revision = ros_node.http.get("/health").json()["kb"]["revision"]
    until(lambda: int(statuses(probe)["situated: KB"]["values"]["revision"]) == revision)  # a later report


def test_a_model_that_does_not_answer_is_an_error_and_the_service_warns(
        ros_node_factory: Callable[..., RosNode], probe: Probe, silent_model: str) -> None:
    ros_node_factory("--scene", "none", "--llm", silent_model, "--ros-args", "-p", "diagnostics_period:=2")
    probe("subscribe", topic="/diagnostics", type=ARRAY)
    found = statuses(probe)
    assert found["situated: model"]["level"] == ERROR and "not reachable" in found["situated: model"]["message"]
    service = found["situated: service"]
    assert service["level"] == WARN and service["message"].startswith(f"model: {silent_model[len('hybrid:'):]} "
                                                                      "is not reachable")
