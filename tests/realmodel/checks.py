"""Plumbing checks shared by the real-model tests (not accuracy)."""

from __future__ import annotations

from typing import Any

from dialogue.engine import TurnResult
from dialogue.intents import RAW_USER_INPUT
from dialogue.reference.grounding import Snapshot
from dialogue.schema import REFERENT_FIELDS, full_name


def assert_grounded(result: TurnResult, snapshot: Snapshot, speaker: str, text: str) -> None:
    """Every intent is the raw-input fallback for `text`, or has only KB ids (or the speaker) as referents."""
    assert result.response.strip(), result
    for intent in result.intents:
        if intent.intent == RAW_USER_INPUT:
            assert intent.data["input"] == text
            continue
        for role in REFERENT_FIELDS:
            value = intent.data.get(role)
            free_text = role == "object" and intent.intent in {"__intent_say__", "__intent_start_activity__"}
            if value is not None and not free_text:
                assert value in snapshot.entities or value == speaker, (role, value, result)


def intent_schemas(schema: dict[str, Any]) -> dict[str, dict[str, Any]]:
    """The properties of each intent object the schema offers, by the catalogue's intent type."""
    variants = schema["properties"]["user_intent"]["anyOf"]
    return {full_name(v["properties"]["type"]["const"]): v["properties"] for v in variants if v.get("type") == "object"}
