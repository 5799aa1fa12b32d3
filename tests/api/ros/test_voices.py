"""Speech in on a real graph (--voices): a voice's final result is a turn of the person whose voice_id
names it (an unknown speaker otherwise), the reply said on /say, the intents on /intents."""

from __future__ import annotations

import json
from collections.abc import Callable

from tests.api.ros.conftest import SCENE, Probe, RosNode
from tests.waiting import until

SPEECH = "hri_msgs/msg/LiveSpeech"
STRING = "std_msgs/msg/String"


def test_a_voice_speaks_for_its_person_and_the_reply_is_said(ros_node_factory: Callable[..., RosNode],
                                                             probe: Probe) -> None:
    node = ros_node_factory("--scene", str(SCENE), "--voices")
    for topic, kind in (("/say", STRING), ("/intents", "hri_actions_msgs/msg/Intent")):
        probe("subscribe", topic=topic, type=kind)
    probe("subscribe", topic="/rosout", type="rcl_interfaces/msg/Log", latched=True)
    probe("publish", topic="/humans/persons/person_alice/voice_id", type=STRING, message={"data": "v1"},
          latched=True)
    until(lambda: any(m["msg"] == "voice v1 is person_alice's" for m in probe.messages("/rosout", timeout=0)))
    speech = "/humans/voices/v1/speech"
    probe("publish", topic=speech, type=SPEECH, message={"incremental": "pick up"})  # not a turn
    probe("publish", topic=speech, type=SPEECH, message={"final": "pick up the cup", "language": "en-GB",
                                                          "confidence": 0.9})
    assert [m["data"] for m in probe.messages("/say")] == ["OK, I will pick up the cup."]
    [grab] = probe.messages("/intents")
    assert (grab["intent"], json.loads(grab["data"]), grab["source"]) == \
        ("__intent_grab_object__", {"object": "cup_1"}, "person_alice")
    # A voice no person claims is an unknown speaker's.
    probe("publish", topic="/humans/voices/v2/speech", type=SPEECH, message={"final": "pick up the book"})
    assert [m["data"] for m in probe.messages("/say", count=2)][1] == "OK, I will pick up the cookbook."
    assert probe.messages("/intents", count=2)[1]["source"] == "__unknown_agent__"
    # Turns of the service's default dialogue, in the speech's language.
    turns = node.http.get("/dialogues/default/turns").json()["turns"]
    assert [(t["speaker"], t["input"], t["locale"]) for t in turns] == [
        ("__unknown_agent__", "pick up the book", None), ("person_alice", "pick up the cup", "en_GB")]
