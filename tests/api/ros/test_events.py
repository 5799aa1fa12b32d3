"""knowledge_core's events over a real graph: /kb/events, a topic per subscription, the first
trigger kept for a client that subscribes late, one-shot, models, refusals and active concepts."""

from __future__ import annotations

import json
import re
import time
from collections.abc import Callable

from tests.api.ros.conftest import Probe, RosNode

EVENT = "kb_msgs/srv/Event"
REVISE = "kb_msgs/srv/Revise"
STRING = "std_msgs/msg/String"


def revise(probe: Probe, *statements: str, method: str = "update", models: list[str] | None = None) -> None:
    answer = probe.call("/kb/revise", REVISE, method=method, statements=list(statements), models=models or [])
    assert answer["success"] is True, answer


def received(probe: Probe, topic: str, count: int, timeout: float = 10.0) -> list[object]:
    messages = probe("messages", topic=topic, count=count, timeout=timeout)["messages"]
    return [json.loads(m["data"]) for m in messages]


def settle(probe: Probe, topic: str, seconds: float = 0.5) -> list[object]:
    """What a topic has received once nothing more should come."""
    time.sleep(seconds)
    return received(probe, topic, 10_000, timeout=0)


def test_a_subscription_has_an_id_and_a_topic_carrying_the_new_rows(ros_node: RosNode, probe: Probe) -> None:
    revise(probe, "joe rdf:type Robot")  # true before: no trigger
    event = probe.call("/kb/events", EVENT, patterns=["?robot rdf:type Robot"])
    assert re.fullmatch(r"evt_[0-9a-f]{32}", event["id"]) and event["topic"] == f"/kb/events/{event['id']}"
    again = probe.call("/kb/events", EVENT, patterns=["?robot rdf:type Robot"])
    assert again == event  # identical subscriptions share id and topic
    probe("subscribe", topic=event["topic"], type=STRING)
    revise(probe, "ari rdf:type Robot", "bill rdf:type Human")
    assert received(probe, event["topic"], 1) == [[{"robot": "ari"}]]
    revise(probe, "ari rdf:type Robot")  # nothing new
    revise(probe, "ari rdf:type Robot", method="retract")
    revise(probe, "ari rdf:type Robot")  # gone and back: new again
    assert settle(probe, event["topic"]) == [[{"robot": "ari"}], [{"robot": "ari"}]]


def test_triggers_before_the_client_subscribed_reach_it_when_it_does(ros_node: RosNode, probe: Probe) -> None:
    # knowledge_core publishes only to a topic that has a subscriber at that moment: a client that
    # has only just subscribed loses the first trigger. Here it is held until the client is seen.
    event = probe.call("/kb/events", EVENT, patterns=["?h rdf:type Human"], one_shot=True)
    revise(probe, "joe rdf:type Human")
    revise(probe, "john rdf:type Human")  # one-shot: over after the first
    time.sleep(0.5)
    probe("subscribe", topic=event["topic"], type=STRING)
    assert received(probe, event["topic"], 1) == [[{"h": "joe"}]]
    assert settle(probe, event["topic"]) == [[{"h": "joe"}]]


def test_a_topic_nobody_listens_to_any_more_is_ended(ros_node: RosNode, probe: Probe) -> None:
    event = probe.call("/kb/events", EVENT, patterns=["?h rdf:type Human"])
    probe("subscribe", topic=event["topic"], type=STRING)
    revise(probe, "joe rdf:type Human")
    assert received(probe, event["topic"], 1) == [[{"h": "joe"}]]
    assert ros_node.http.get("/health").json()["events"]["subscribers"] == 1
    probe("unsubscribe", topic=event["topic"])
    deadline = time.monotonic() + 10
    while ros_node.http.get("/health").json()["events"]["subscribers"] and time.monotonic() < deadline:
        time.sleep(0.05)
    assert ros_node.http.get("/health").json()["events"]["subscribers"] == 0  # its subscription given back
    probe("subscribe", topic=event["topic"], type=STRING)
    revise(probe, "bill rdf:type Human")  # as knowledge_core: the event is gone, nothing comes
    assert settle(probe, event["topic"]) == []
    assert "nobody listens to /kb/events/" in ros_node.server.log.read_text()


def test_a_subscription_in_a_model(ros_node: RosNode, probe: Probe) -> None:
    revise(probe, "alice_mind knows cup_1", models=["alice"])
    event = probe.call("/kb/events", EVENT, patterns=["?x isOn ?y"], models=["alice"])
    assert event["id"] != probe.call("/kb/events", EVENT, patterns=["?x isOn ?y"])["id"]
    probe("subscribe", topic=event["topic"], type=STRING)
    revise(probe, "book_9 isOn shelf_9")  # the robot's own model
    revise(probe, "cup_1 isOn table_1", models=["alice"])
    assert received(probe, event["topic"], 1) == [[{"x": "cup_1", "y": "table_1"}]]
    assert settle(probe, event["topic"]) == [[{"x": "cup_1", "y": "table_1"}]]


def test_a_refused_subscription_answers_no_id_and_the_node_logs_why(
        ros_node_factory: Callable[..., RosNode], probe: Probe) -> None:
    node = ros_node_factory(env={"SITUATED_LIMITS__MAX_SUBSCRIBERS": "1", "SITUATED_LIMITS__MAX_PATTERNS": "2"})
    assert probe.call("/kb/events", EVENT, patterns=["toto"]) == {"id": "", "topic": ""}
    assert probe.call("/kb/events", EVENT, patterns=[f"?x likes thing_{n}" for n in range(3)]) == {
        "id": "", "topic": ""}
    assert probe.call("/kb/events", EVENT, patterns=[]) == {"id": "", "topic": ""}
    assert probe.call("/kb/events", EVENT, patterns=["?a likes ?b"])["id"]
    assert probe.call("/kb/events", EVENT, patterns=["?a hates ?b"]) == {"id": "", "topic": ""}
    log = node.server.log.read_text()
    assert "/kb/events refused ['toto']: " in log and "3 patterns in one request; the limit is 2" in log
    assert "at least one pattern" in log and "the limit is 1" in log


def test_active_concepts_are_published_when_they_change(ros_node: RosNode, probe: Probe) -> None:
    # Latched: a subscriber that comes after a change still gets the current set.
    probe("subscribe", topic="/kb/active_concepts", type="kb_msgs/msg/ActiveConcepts", latched=True)
    revise(probe, "cup_1 rdf:type ActiveConcept")
    assert [m["concepts"] for m in probe("messages", topic="/kb/active_concepts", count=1)["messages"]] == [
        ["cup_1"]]
    revise(probe, "book_1 rdf:type ActiveConcept")
    messages = probe("messages", topic="/kb/active_concepts", count=2, timeout=10)["messages"]
    assert [m["concepts"] for m in messages] == [["cup_1"], ["book_1", "cup_1"]]
