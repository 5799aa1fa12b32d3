"""/intents on a real graph: every intent the service emits — a ROS turn's, a REST turn's, a 4.0
stateless turn's, the initiative's greeting — as hri_actions_msgs/Intent, in the intent bus's order."""

from __future__ import annotations

import json
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from tests.api.ros.conftest import Probe, RosNode
from tests.waiting import until

INTENT = "hri_actions_msgs/msg/Intent"


def fields(message: dict[str, Any]) -> tuple[str, dict[str, Any], str]:
    return message["intent"], json.loads(message["data"]), message["source"]


def test_every_intent_of_every_dialogue_and_of_the_initiative_in_order(ros_node: RosNode, probe: Probe) -> None:
    probe("subscribe", topic="/intents", type=INTENT)
    first = ros_node.http.get("/intents").json()["last_seq"]
    # The initiative: Tom becomes engaged (any producer's fact), the robot engages and greets him.
    written = probe.call("/kb/revise", "kb_msgs/srv/Revise", method="update",
                         statements=["person_tom engagementLevel engaged"])
    assert written["success"]
    greeting = probe.messages("/intents", count=2)
    assert [fields(m) for m in greeting] == [
        ("__intent_engage_with__", {"recipient": "person_tom"}, "__myself__"),
        ("__intent_greet__", {"recipient": "person_tom"}, "__myself__")]
    assert (greeting[0]["modality"], greeting[0]["priority"], greeting[0]["confidence"]) == \
        ("__modality_motion__", 128, 1.0)
    # A turn over ROS, one over REST, a 4.0 stateless one.
    probe.call("/chatbot/dialogue_interaction", "chatbot_msgs/srv/DialogueInteraction", dialogue_id={"uuid": [0] * 16},
               user_id="person_alice", input="pick up the cup", response_expected=True)
    assert ros_node.http.post("/dialogues/default/interactions", json={
        "user_id": "person_alice", "input": "pick up the book"}).status_code == 200
    assert ros_node.http.post("/dialogues/dm-1/interactions", json={"role": {"name": "__default__"}, "history": [
        {"speaker": "person_tom", "text": "bring me the cup"}]}).status_code == 200
    turns = probe.messages("/intents", count=5)[2:]
    assert [fields(m) for m in turns] == [
        ("__intent_grab_object__", {"object": "cup_1"}, "person_alice"),
        ("__intent_grab_object__", {"object": "book_1"}, "person_alice"),
        ("__intent_bring_object__", {"object": "cup_1", "recipient": "person_tom"}, "person_tom")]
    # Many turns at once: /intents in the order the bus numbered them.
    def turn(n: int) -> int:
        said = {"speaker": ("person_alice", "person_tom")[n % 2], "text": ("pick up the cup", "pick up the book")[n // 2 % 2]}
        return ros_node.http.post(f"/dialogues/many-{n}/interactions", json={
            "role": {"name": "__default__"}, "history": [said]}).status_code

    with ThreadPoolExecutor(4) as pool:
        assert set(pool.map(turn, range(16))) == {200}
    published = probe.messages("/intents", count=5 + 16)
    numbered = ros_node.http.get("/intents", params={"after": first}).json()["intents"]
    assert [fields(m) for m in published] == [
        (e["intent"]["intent"], e["intent"]["data"], e["intent"]["source"]) for e in numbered]
    assert len(published) == 5 + 16


def test_an_intent_with_json_values_is_published_with_them(ros_node: RosNode, probe: Probe) -> None:
    """`data` is a JSON string: values of any JSON type (an object in `other_data`) are in it as
    they were pushed."""
    probe("subscribe", topic="/intents", type=INTENT)
    until(lambda: probe("publisher_count", topic="/intents")["matched"])  # else the message may go before
    data = {"object": "memory_game", "other_data": {"level": 2, "players": ["person_tom"], "timed": False}}
    pushed = ros_node.http.post("/intents", json={"intent": {"intent": "__intent_start_activity__", "data": data,
                                                             "source": "person_tom", "priority": 200}})
    assert pushed.status_code == 200, pushed.text
    [message] = probe.messages("/intents", count=1)
    assert fields(message) == ("__intent_start_activity__", data, "person_tom")
    assert message["priority"] == 200
