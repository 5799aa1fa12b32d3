"""Speech in, behind ``--voices`` (parameter ``voices``): what a voice says is a turn of its person,
the reply said on ``/say`` (std_msgs/String), as the IROS22 bridge did — situated as its own hub,
without communication_hub or dialogue_manager.

``/humans/voices/<id>/speech`` (hri_msgs/LiveSpeech) gives text; only ``final`` results are turns
(``incremental`` ones are the recogniser changing its mind). The speaker is the person whose
``/humans/persons/<id>/voice_id`` (latched) names that voice, as ROS4HRI's person manager says; a voice
no person claims is an unknown speaker (``__unknown_agent__``). The turn is one of the service's
``default`` dialogue — the conversation of the people around the robot, the one REST and the
viewer's chat share — in the speech's language (or the node's ``default_locale``), with the node's
``turn_deadline``. Its intents go to ``/intents`` as every turn's do. A final result longer than
REST takes (``max_input_chars``) is dropped, with a warning.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from concurrent.futures import Future
from typing import Any

from hri_msgs.msg import LiveSpeech
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup
from rclpy.qos import QoSDurabilityPolicy, QoSProfile, QoSReliabilityPolicy
from std_msgs.msg import String

from api.ros.node.discovery import TopicWatch
from api.ros.node.front import Front
from dialogue.engine import TurnResult
from dialogue.errors import DialogueError, SessionError
from dialogue.intents import UNKNOWN_AGENT
from dialogue.sessions.entries import entry_locale
from dialogue.sessions.store import DEFAULT_DIALOGUE

log = logging.getLogger("situated.ros")
SPEECH = r"/humans/voices/([^/]+)/speech"
VOICE_IDS = r"/humans/persons/([^/]+)/voice_id"
#: ROS4HRI's person topics are latched: a late subscriber still gets the last value.
LATCHED = QoSProfile(depth=1, reliability=QoSReliabilityPolicy.RELIABLE,
                     durability=QoSDurabilityPolicy.TRANSIENT_LOCAL)


class Voices:
    """Who speaks with which voice, and the turns of what they say (callbacks one at a time)."""

    def __init__(self, front: Front, say: Callable[[Any], None]) -> None:
        self.front = front
        self.dialogues = front.services.dialogues
        self.limit = front.services.settings.limits.max_input_chars
        self.say = say
        #: Each person's voice, as their voice_id topic says.
        self.voice_of: dict[str, str] = {}

    def person_of(self, voice: str) -> str:
        people = sorted(person for person, heard in self.voice_of.items() if heard == voice)
        return people[0] if people else UNKNOWN_AGENT

    def voice_id(self, person: str, message: Any) -> None:
        if message.data:
            self.voice_of[person] = message.data
            self.front.chatbot_node.get_logger().info(f"voice {message.data} is {person}'s")
        else:  # the person manager's "no voice now"
            self.voice_of.pop(person, None)

    def heard(self, voice: str, message: Any) -> None:
        text = message.final.strip()
        if not text:
            return
        if len(text) > self.limit:
            log.warning("speech of voice %s dropped: %d characters, the limit is %d (max_input_chars)",
                        voice, len(text), self.limit)
            return
        try:
            locale = entry_locale(message.language) or self.front.default_locale()
        except SessionError:
            locale = self.front.default_locale()
        turn = self.dialogues.interact(self.person_of(voice), text, dialogue_id=DEFAULT_DIALOGUE,
                                       locale=locale, timeout=self.front.parameters.turn_deadline)
        # Not waited for here: the reply is said when the turn ends (turns of one dialogue are
        # answered in their order), and this callback is free for the next result.
        asyncio.run_coroutine_threadsafe(turn, self.front.loop).add_done_callback(self._answered)

    def _answered(self, done: Future[TurnResult]) -> None:
        try:
            result = done.result()
        except DialogueError as exc:
            log.warning("a voice's turn was refused: %s", exc)
            return
        if result.response:
            self.say(String(data=result.response))

    def forget(self, person: str) -> None:
        self.voice_of.pop(person, None)


def attach(front: Front) -> Callable[[], None]:
    if not front.parameters.voices:
        return lambda: None
    node = front.chatbot_node
    group = MutuallyExclusiveCallbackGroup()
    publisher = node.create_publisher(String, "/say", 10)
    voices = Voices(front, publisher.publish)
    speech = TopicWatch(node, SPEECH, lambda voice, topic: node.create_subscription(
        LiveSpeech, topic, lambda message: voices.heard(voice, message), 10, callback_group=group),
        lambda voice, topic, made: node.destroy_subscription(made), group)

    def person_gone(person: str, topic: str, made: Any) -> None:
        node.destroy_subscription(made)
        voices.forget(person)

    ids = TopicWatch(node, VOICE_IDS, lambda person, topic: node.create_subscription(
        String, topic, lambda message: voices.voice_id(person, message), LATCHED, callback_group=group),
        person_gone, group)

    def detach() -> None:
        speech.close()
        ids.close()
        node.destroy_publisher(publisher)

    return detach
