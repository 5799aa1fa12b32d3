"""The ROS front: two nodes on one graph that stays on this machine, stopped cleanly with the service."""

from __future__ import annotations

import signal

import psutil

from api.ros.prefix import LOCAL_DISCOVERY
from tests.api.ros.conftest import Probe, RosNode


def _environ(pid: int) -> dict[str, str]:
    return psutil.Process(pid).environ()


def test_the_graph_stays_on_this_machine_in_a_domain_of_its_own(ros_node: RosNode, probe: Probe,
                                                                 ros_domain: int) -> None:
    # Every process of the graph (the node and its client) discovers on localhost only, in the
    # test's domain: Fast DDS would otherwise multicast on every interface.
    for env in (_environ(ros_node.server.proc.pid), probe("env")["env"]):
        assert env["ROS_AUTOMATIC_DISCOVERY_RANGE"] == LOCAL_DISCOVERY
        assert env["ROS_DOMAIN_ID"] == str(ros_domain)
    status = probe.call("/kb/manage", "kb_msgs/srv/Manage", action="status")
    assert status["success"] is True


def test_the_node_and_the_http_service_share_one_kb(ros_node: RosNode, probe: Probe) -> None:
    assert ros_node.http.post("/kb/revise", json={"statements": ["ari rdf:type Robot"],
                                                  "method": "add"}).status_code == 200
    answer = probe.call("/kb/query", "kb_msgs/srv/Query", patterns=["?s rdf:type Robot"])
    assert {"s": "ari"} in __import__("json").loads(answer["json"])
    written = probe.call("/kb/revise", "kb_msgs/srv/Revise", method="update", statements=["bob likes tea"])
    assert written["success"] is True
    assert ros_node.http.post("/kb/query", json={"patterns": ["bob likes ?x"]}).json() == [{"x": "tea"}]


def test_sigterm_stops_http_and_ros_cleanly(ros_node: RosNode, probe: Probe) -> None:
    probe.call("/kb/manage", "kb_msgs/srv/Manage", action="status")
    ros_node.server.proc.send_signal(signal.SIGTERM)
    # uvicorn re-raises the signal once it has shut down: the exit status is SIGTERM's either way.
    assert ros_node.server.proc.wait(30) == -signal.SIGTERM
    log = ros_node.server.log.read_text()
    assert "ROS 2 node up" in log and "Application shutdown complete" in log
    assert "Traceback" not in log and "terminate called" not in log
