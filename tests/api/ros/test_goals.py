"""/chatbot/start_dialogue (chatbot_msgs Dialogue) on a real graph: a goal is a dialogue of the service
under its UUID, active while the dialogue is open, ended with its results — a completed form, a
cancel, an abort — and a goal the service cannot play is rejected, the reason on /rosout."""

from __future__ import annotations

import json
import signal
import uuid
from typing import Any

from tests.api.ros.conftest import Probe, RosNode
from tests.waiting import until

ACTION = "/chatbot/start_dialogue"
DIALOGUE = "chatbot_msgs/action/Dialogue"
INTERACTION = "/chatbot/dialogue_interaction"
DI = "chatbot_msgs/srv/DialogueInteraction"
AGE = json.dumps({"question": "How old are you?", "result_schema_properties": {"age": {"type": "integer", "minimum": 0}}})


def start(probe: Probe, name: str = "__default__", configuration: str = "{}", locale: str = "") -> dict[str, Any]:
    return probe("goal", action=ACTION, type=DIALOGUE,
                 goal={"role": {"name": name, "configuration": configuration}, "locale": locale})


def say(probe: Probe, goal: str, user: str, text: str) -> dict[str, Any]:
    return probe.call(INTERACTION, DI, dialogue_id={"uuid": list(uuid.UUID(goal).bytes)}, user_id=user,
                      input=text, response_expected=True)


def test_an_ask_goal_is_the_dialogue_rest_sees_and_succeeds_with_the_form_filled(ros_node: RosNode,
                                                                                probe: Probe) -> None:
    goal = start(probe, "__ask__", AGE, "en_GB")
    assert goal["accepted"]
    dialogue_id = str(uuid.UUID(goal["goal"]))
    # The robot speaks first when the dialogue manager prompts it (a system update, nothing said).
    assert say(probe, goal["goal"], "__system__", "")["response"] == "How old are you?"
    assert probe("status", goal=goal["goal"])["status"] == "accepted"  # active while the dialogue is open
    # The same dialogue over REST, under the goal's UUID: its answer fills the form.
    answer = ros_node.http.post(f"/dialogues/{dialogue_id}/interactions",
                                json={"user_id": "person_alice", "input": "I am 40"}).json()
    assert answer["dialogue_terminal"] is True
    done = probe("result", goal=goal["goal"])
    assert done["status"] == "succeeded"
    assert json.loads(done["result"]["results"]) == {"age": 40} and done["result"]["error_msg"] == ""
    status = ros_node.http.get(f"/dialogues/{dialogue_id}").json()  # REST reads the same end
    assert (status["status"], status["results"], status["error_msg"]) == ("done", done["result"]["results"], "")
    turns = ros_node.http.get(f"/dialogues/{dialogue_id}/turns").json()["turns"]
    assert turns[0]["locale"] == "en_GB"


def test_a_cancelled_goal_ends_its_dialogue_with_what_was_obtained(ros_node: RosNode, probe: Probe) -> None:
    goal = start(probe)
    assert say(probe, goal["goal"], "person_alice", "pick up the cup")["intents"][0]["intent"] == \
        "__intent_grab_object__"
    assert probe("cancel", goal=goal["goal"])["cancelling"] == 1
    ended = probe("result", goal=goal["goal"])
    assert ended["status"] == "canceled" and ended["result"] == {"results": "{}", "error_msg": ""}
    gone = say(probe, goal["goal"], "person_alice", "pick up the book")
    assert gone["intents"] == [] and "unknown dialogue" in gone["error_msg"]
    assert ros_node.http.get(f"/dialogues/{uuid.UUID(goal['goal'])}/turns").status_code == 404


def test_a_goal_is_aborted_when_the_person_calls_it_off_or_its_dialogue_is_ended_elsewhere(
        ros_node: RosNode, probe: Probe) -> None:
    asked, other = start(probe, "__ask__", AGE), start(probe)
    say(probe, asked["goal"], "person_alice", "never mind")
    called_off = probe("result", goal=asked["goal"])
    assert called_off["status"] == "aborted" and "called the dialogue off" in called_off["result"]["error_msg"]
    status = ros_node.http.get(f"/dialogues/{uuid.UUID(asked['goal'])}").json()  # REST reads the same end
    assert (status["status"], status["results"], status["error_msg"]) == (
        "cancelled", called_off["result"]["results"], called_off["result"]["error_msg"])
    assert ros_node.http.delete(f"/dialogues/{uuid.UUID(other['goal'])}").status_code == 200
    ended = probe("result", goal=other["goal"])
    assert ended["status"] == "aborted" and "ended elsewhere" in ended["result"]["error_msg"]


def test_a_goal_the_service_cannot_play_is_rejected_and_the_reason_logged(ros_node: RosNode, probe: Probe) -> None:
    probe("subscribe", topic="/rosout", type="rcl_interfaces/msg/Log", latched=True)
    refused = [("__poet__", "{}", "", "unsupported dialogue role '__poet__'"),
               ("__ask__", "{}", "", "the ask role needs a question"),
               ("__default__", "not json", "", "configuration is not JSON"),
               ("__default__", "{}", "klingon please", "not a language tag")]
    for name, configuration, locale, _why in refused:
        assert start(probe, name, configuration, locale)["accepted"] is False

    def logged() -> list[str]:
        return [m["msg"] for m in probe.messages("/rosout", timeout=0.1)
                if m["name"] == "chatbot" and "start_dialogue goal rejected" in m["msg"]]

    reasons = until(lambda: len(logged()) == len(refused) and logged())
    for (_name, _configuration, _locale, why), reason in zip(refused, reasons, strict=True):
        assert why in reason


def test_a_goal_open_when_the_service_stops_is_aborted(ros_node: RosNode, probe: Probe) -> None:
    goal = start(probe)
    ros_node.server.proc.send_signal(signal.SIGTERM)
    ended = probe("result", goal=goal["goal"])
    assert ended["status"] == "aborted" and ended["result"]["error_msg"] == "the service is stopping"
