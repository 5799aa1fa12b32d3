"""Perception in on a real graph: /humans/persons/<id>/engagement_status as the KB's engagement facts,
discovered as the person's topic appears, so the initiative engages and greets a real robot's people."""

from __future__ import annotations

import json

from tests.api.ros.conftest import Probe, RosNode
from tests.waiting import until

LEVEL = "hri_msgs/msg/EngagementLevel"
QUERY = "kb_msgs/srv/Query"
UNKNOWN, DISENGAGED, ENGAGING, ENGAGED = 0, 1, 2, 3


def level_of(probe: Probe, person: str) -> list[str]:
    rows = json.loads(probe.call("/kb/query", QUERY, patterns=[f"{person} engagementLevel ?l"])["json"])
    return [row["l"] for row in rows]


def test_levels_become_facts_and_the_robot_engages_and_greets(ros_node: RosNode, probe: Probe) -> None:
    probe("subscribe", topic="/intents", type="hri_actions_msgs/msg/Intent")
    assert probe.call("/kb/revise", "kb_msgs/srv/Revise", method="update",
                      statements=['a1b2c rdfs:label "Ana"'])["success"]
    topic = "/humans/persons/a1b2c/engagement_status"
    probe("publish", topic=topic, type=LEVEL, message={"level": ENGAGING})  # once the node subscribed
    until(lambda: level_of(probe, "a1b2c") == ["engaging"])
    for _ in range(3):  # hri_engagement repeats the level at 10 Hz: one change, one fact
        probe("publish", topic=topic, type=LEVEL, message={"level": ENGAGED})
    until(lambda: level_of(probe, "a1b2c") == ["engaged"])
    intents = probe.messages("/intents", count=2)
    assert [(m["intent"], json.loads(m["data"])) for m in intents] == [
        ("__intent_engage_with__", {"recipient": "a1b2c"}), ("__intent_greet__", {"recipient": "a1b2c"})]
    said = ros_node.http.get("/intents").json()["intents"][-1]["response"]
    assert said == "Hello Ana!"
    assert {"p": "a1b2c"} in json.loads(probe.call("/kb/query", QUERY, patterns=["?p rdf:type Human"])["json"])
    probe("publish", topic=topic, type=LEVEL, message={"level": DISENGAGED})
    until(lambda: level_of(probe, "a1b2c") == ["disengaged"])
    probe("publish", topic=topic, type=LEVEL, message={"level": UNKNOWN})
    until(lambda: level_of(probe, "a1b2c") == [])
    assert len(probe.messages("/intents", timeout=0.1)) == 2  # the same change is written once, engaged once


def test_a_person_nobody_reports_any_more_has_no_level_and_speech_is_not_heard_without_voices(
        ros_node: RosNode, probe: Probe) -> None:
    topic = "/humans/persons/f00d1/engagement_status"
    probe("publish", topic=topic, type=LEVEL, message={"level": DISENGAGED})
    until(lambda: level_of(probe, "f00d1") == ["disengaged"])
    probe("unpublish", topic=topic)  # the perception node forgets the person
    until(lambda: level_of(probe, "f00d1") == [])
    # The node watches the persons' topics, not the voices' unless asked to (--voices).
    probe("publish", topic="/humans/voices/v1/speech", type="hri_msgs/msg/LiveSpeech", message={"final": "hi"},
          subscribers=0)
    probe("publish", topic="/humans/persons/f00d2/engagement_status", type=LEVEL, message={"level": ENGAGING})
    until(lambda: level_of(probe, "f00d2") == ["engaging"])  # a look at the graph since the voice came
    assert probe("subscribers", topic="/humans/voices/v1/speech")["count"] == 0
