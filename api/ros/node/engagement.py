"""Perception in: ``/humans/persons/<id>/engagement_status`` (hri_msgs/EngagementLevel, from
hri_engagement) as the KB's engagement facts, which the robot's initiative reacts to.

Each level the person reaches is ``<id> engagementLevel <level>`` in the robot's model (ORO's
individuals: disengaged, engaging, engaged, disengaging; a functional property, so the new level
replaces the old), the person made a ``Human`` of the KB first if the KB does not know them (as a
speaker is). UNKNOWN, or nobody publishing the person's topic any more, retracts the level.
hri_engagement publishes at 10 Hz: only a change is written. The person id is ROS4HRI's, verbatim.
Becoming ``engaged`` is what the initiative (dialogue.initiative) engages with and greets.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import Any

from hri_msgs.msg import EngagementLevel
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup
from rdflib import URIRef

from api.ros.node.discovery import TopicWatch
from api.ros.node.front import Front
from dialogue.initiative import ENGAGEMENT
from dialogue.speakers import admit
from kb import KbError
from kb.protocol import KnowledgeBase
from kb.terms import ORO, format_term, format_triple, parse_name
from scene.engagement import Level

log = logging.getLogger("situated.ros")
TOPICS = r"/humans/persons/([^/]+)/engagement_status"


class Engagement:
    """The last level written per person (callbacks run one at a time: one callback group)."""

    def __init__(self, kb: KnowledgeBase) -> None:
        self.kb = kb
        self.levels: dict[str, Level] = {}

    def heard(self, person: str, message: Any) -> None:
        try:
            level = Level(message.level)
        except ValueError:
            log.warning("engagement of %s: %r is no EngagementLevel; ignored", person, message.level)
            return
        if self.levels.get(person, Level.UNKNOWN) is level:
            return
        try:
            self._write(person, level)
        except KbError as exc:  # the next message tries again
            log.warning("engagement of %s not written: %s", person, exc)
            return
        self.levels[person] = level

    def forget(self, person: str) -> None:
        if self.levels.pop(person, Level.UNKNOWN) is not Level.UNKNOWN:
            try:
                self._write(person, Level.UNKNOWN)
            except KbError as exc:
                log.warning("engagement of %s not retracted: %s", person, exc)

    def _write(self, person: str, level: Level) -> None:
        subject = parse_name(person, "person id")
        if level.individual is None:
            self.kb.remove([f"{format_term(subject)} {format_term(ENGAGEMENT)} ?level"])
            return
        admit(self.kb, person)
        self.kb.update([format_triple((subject, ENGAGEMENT, URIRef(ORO + level.individual)))])


def attach(front: Front) -> Callable[[], None]:
    node = front.chatbot_node
    group = MutuallyExclusiveCallbackGroup()  # in order, one at a time
    engagement = Engagement(front.services.kb)

    def appeared(person: str, topic: str) -> Any:
        def heard(message: Any) -> None:
            engagement.heard(person, message)

        return node.create_subscription(EngagementLevel, topic, heard, 10, callback_group=group)

    def gone(person: str, topic: str, subscription: Any) -> None:
        node.destroy_subscription(subscription)
        engagement.forget(person)

    watch = TopicWatch(node, TOPICS, appeared, gone, group)
    return watch.close
