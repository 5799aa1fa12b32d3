"""The chatbot's dialogues on ``/chatbot`` (chatbot_msgs 3.0): the Dialogue action (node.goals) and
DialogueInteraction (node.interaction), on the service's own dialogues: a dialogue started over ROS
is the one REST sees under the goal's UUID, and the other way round for its turns."""

from __future__ import annotations

from collections.abc import Callable

from chatbot_msgs.srv import DialogueInteraction

from api.ros.node.front import Front
from api.ros.node.goals import DialogueGoals
from api.ros.node.interaction import Interaction


def attach(front: Front) -> Callable[[], None]:
    node = front.chatbot_node
    goals = DialogueGoals(front)
    service = node.create_service(DialogueInteraction, "~/dialogue_interaction", Interaction(front, goals))

    def detach() -> None:
        node.destroy_service(service)
        goals.close()

    return detach
