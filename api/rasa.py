"""The Rasa-compatible facade's shapes (dialogue-compat §7): REST channel messages and NLU parse.

Pure functions from a dialogue turn's result to what a client of ``rasa run`` expects.
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable, Sequence
from typing import Any

from dialogue.intents import RAW_USER_INPUT, Intent

_BLANK_LINES = re.compile(r"\n\s*\n")
REFERENT_ROLES = ("object", "recipient", "goal")


def dialogue_key(sender: str) -> str:
    """The dialogue a Rasa conversation (``sender``) maps to."""
    return f"rasa:{sender}"


def webhook_messages(sender: str, response: str, intents: Sequence[Intent]) -> list[dict[str, Any]]:
    """``[{"recipient_id", "text"}, ...]``: the reply split at blank lines (as Rasa does); the intents
    ride in ``custom`` on the last message (or on a message of their own when there is no text)."""
    texts = [part.strip() for part in _BLANK_LINES.split(response) if part.strip()]
    messages: list[dict[str, Any]] = [{"recipient_id": sender, "text": text} for text in texts]
    if intents:
        custom = {"intents": [intent.model_dump() for intent in intents]}
        if messages:
            messages[-1]["custom"] = custom
        else:
            messages.append({"recipient_id": sender, "custom": custom})
    return messages


def _span(text: str, names: Sequence[str]) -> tuple[int, int]:
    lowered = text.lower()
    for name in names:
        for candidate in (name, name.replace("_", " ")):
            at = lowered.find(candidate.lower()) if candidate else -1
            if at >= 0:
                return at, at + len(candidate)
    return 0, 0


def parse_result(text: str, intents: Sequence[Intent], label: Callable[[str], str]) -> dict[str, Any]:
    """Rasa's ``/model/parse`` answer. ``label(id)`` gives an entity's name, to find it in the text; a
    role whose value is no string (JSON in ``other_data``) is an entity whose value is its JSON text."""
    ranking = [{"name": i.intent, "confidence": i.confidence} for i in intents]
    top = intents[0] if intents else None
    intent = ranking[0] if ranking else {"name": RAW_USER_INPUT, "confidence": 0.0}
    entities = []
    if top is not None and top.intent != RAW_USER_INPUT:
        for role, value in top.data.items():
            if isinstance(value, str):
                names = [value, label(value)] if role in REFERENT_ROLES else [value]
                start, end = _span(text, names)
            else:  # a JSON value (other_data...): Rasa's entity value is text, and no words say it
                value, (start, end) = json.dumps(value, ensure_ascii=False), (0, 0)
            entities.append({"start": start, "end": end, "value": value, "entity": role,
                             "confidence": top.confidence})
    return {"text": text, "intent": intent, "entities": entities, "intent_ranking": ranking}
