"""The service's values as ROS messages and back: dialogue ids as UUIDs, intents as
hri_actions_msgs/Intent (``data`` the JSON string of the REST shape's object)."""

from __future__ import annotations

import uuid
from collections.abc import Iterable
from typing import Any

from hri_actions_msgs.msg import Intent as IntentMessage

from dialogue.intents import Intent
from dialogue.sessions.store import DEFAULT_DIALOGUE

#: The nil UUID (all zeros, an unset ROS field) addresses the service's `default` dialogue, which
#: always exists: a caller that starts no dialogue talks in the one REST and the viewer share.
NIL = uuid.UUID(int=0)


def dialogue_id(message: Any) -> str:
    """The dialogue a unique_identifier_msgs/UUID names: its canonical text form (as REST sees it),
    or `default` for the nil UUID."""
    value = uuid.UUID(bytes=bytes(message.uuid))
    return DEFAULT_DIALOGUE if value == NIL else str(value)


def intent_message(intent: Intent) -> Any:
    message = IntentMessage()
    message.intent = intent.intent
    message.data = intent.data_json()
    message.source = intent.source
    message.modality = intent.modality
    message.priority = intent.priority
    message.confidence = float(intent.confidence)
    return message


def intent_messages(intents: Iterable[Intent]) -> list[Any]:
    return [intent_message(intent) for intent in intents]
