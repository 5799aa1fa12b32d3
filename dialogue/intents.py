"""The hri_actions_msgs/Intent 2.5.0 catalogue and the intent model the service emits.

The roles table is the canonical one of `Intent.msg` 2.5.0 (see dialogue-compat §1.2); `agent` may be
added to every intent. `data` is a JSON object (the ROS message carries it as a JSON string): the
roles that name someone or something — the grounded roles, which hold KB entity ids, and `agent` —
and the raw input's `input` and `locale` are text; the other roles (`other_data`, the SAY text,
activity, motion and content names) may hold any JSON value, within dialogue.jsonvalues' bounds.
No role is null: a role with no value is left out (D7).

>>> make_intent(START_ACTIVITY, {"object": "memory_game", "other_data": {"level": 2, "players": ["ana"]}},
...             source="person_ana", confidence=1.0).data_json()
'{"object": "memory_game", "other_data": {"level": 2, "players": ["ana"]}}'
>>> make_intent(GREET, {"recipient": 7}, source="person_ana", confidence=1.0)
Traceback (most recent call last):
    ...
dialogue.intents.IntentError: data.recipient of __intent_greet__ names an entity: a string (a KB id), not 7
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Annotated, Any

from pydantic import BaseModel, ConfigDict, Field, JsonValue, field_validator, model_validator

from dialogue.errors import DialogueError
from dialogue.jsonvalues import JsonValueError
from dialogue.jsonvalues import check as check_json

RAW_USER_INPUT = "__raw_user_input__"
ENGAGE_WITH = "__intent_engage_with__"
MOVE_TO = "__intent_move_to__"
GUIDE = "__intent_guide__"
GRAB_OBJECT = "__intent_grab_object__"
BRING_OBJECT = "__intent_bring_object__"
PLACE_OBJECT = "__intent_place_object__"
GREET = "__intent_greet__"
SAY = "__intent_say__"
PRESENT_CONTENT = "__intent_present_content__"
PERFORM_MOTION = "__intent_perform_motion__"
START_ACTIVITY = "__intent_start_activity__"
STOP_ACTIVITY = "__intent_stop_activity__"
WAKEUP = "__intent_wakeup__"
SUSPEND = "__intent_suspend__"

ROBOT_ITSELF = "__myself__"
REMOTE_SUPERVISOR = "__remote_supervisor__"
UNKNOWN_AGENT = "__unknown_agent__"
UNKNOWN = "__unknown__"
SOURCES = frozenset({ROBOT_ITSELF, REMOTE_SUPERVISOR, UNKNOWN_AGENT, UNKNOWN})

MODALITY_SPEECH = "__modality_speech__"
MODALITY_MOTION = "__modality_motion__"
MODALITY_TOUCHSCREEN = "__modality_touchscreen__"
MODALITY_OTHER = "__modality_other__"
MODALITY_INTERNAL = "__modality_internal__"
MODALITIES = frozenset(
    {MODALITY_SPEECH, MODALITY_MOTION, MODALITY_TOUCHSCREEN, MODALITY_OTHER, MODALITY_INTERNAL}
)

DEFAULT_PRIORITY = 128

#: Keys allowed in `data` (D7): thematic roles, the catch-all, and the raw-input fields.
THEMATIC_ROLES = frozenset({"agent", "object", "goal", "recipient", "other_data"})
RAW_INPUT_ROLES = frozenset({"input", "locale"})
#: Roles whose value is text whatever the intent (with each intent's grounded roles).
TEXT_ROLES = RAW_INPUT_ROLES | {"agent"}


@dataclass(frozen=True)
class IntentSpec:
    """One row of the Intent.msg roles table, plus which roles must be KB entities."""

    name: str
    value: str
    meaning: str
    required: tuple[str, ...]
    optional: tuple[str, ...] = ()
    grounded: tuple[str, ...] = ()

    @property
    def roles(self) -> tuple[str, ...]:
        return (*self.required, *self.optional)


CATALOGUE: dict[str, IntentSpec] = {
    spec.value: spec
    for spec in (
        IntentSpec(
            "RAW_USER_INPUT", RAW_USER_INPUT, "input received, no intent extracted", ("input",), ("locale",)
        ),
        IntentSpec(
            "ENGAGE_WITH", ENGAGE_WITH, "engage with an agent", ("recipient",), grounded=("recipient",)
        ),
        IntentSpec("MOVE_TO", MOVE_TO, "navigate to a location", ("goal",), grounded=("goal",)),
        IntentSpec(
            "GUIDE", GUIDE, "guide someone somewhere", ("goal", "recipient"), grounded=("goal", "recipient")
        ),
        IntentSpec(
            "GRAB_OBJECT", GRAB_OBJECT, "pick up a specific object", ("object",), grounded=("object",)
        ),
        IntentSpec(
            "BRING_OBJECT",
            BRING_OBJECT,
            "bring an object to someone or somewhere",
            ("object", "recipient"),
            grounded=("object", "recipient"),
        ),
        IntentSpec(
            "PLACE_OBJECT",
            PLACE_OBJECT,
            "put an object on a support",
            ("recipient",),
            ("object",),
            grounded=("recipient", "object"),
        ),
        IntentSpec("GREET", GREET, "greet an agent", ("recipient",), grounded=("recipient",)),
        IntentSpec("SAY", SAY, "say some text", ("object",), ("recipient",), grounded=("recipient",)),
        IntentSpec(
            "PRESENT_CONTENT",
            PRESENT_CONTENT,
            "present predefined content",
            ("object",),
            ("recipient",),
            grounded=("recipient",),
        ),
        IntentSpec(
            "PERFORM_MOTION",
            PERFORM_MOTION,
            "perform a motion or gesture",
            ("object",),
            ("recipient",),
            grounded=("recipient",),
        ),
        IntentSpec(
            "START_ACTIVITY",
            START_ACTIVITY,
            "start a scripted activity (following someone: whom, the recipient)",
            ("object",),
            ("recipient", "other_data"),
            grounded=("recipient",),
        ),
        IntentSpec(
            "STOP_ACTIVITY", STOP_ACTIVITY, "stop an activity (the current one by default)", (), ("object",)
        ),
        IntentSpec("WAKEUP", WAKEUP, "reactivate the system", ()),
        IntentSpec("SUSPEND", SUSPEND, "suspend the system", ()),
    )
}

#: Intents the dialogue engine may extract from speech (RAW_USER_INPUT is the fallback, not a choice).
EXTRACTABLE: tuple[str, ...] = tuple(v for v in CATALOGUE if v != RAW_USER_INPUT)


class IntentError(DialogueError, ValueError):
    """An intent that violates the Intent.msg contract (unknown role, missing required role...)."""


def spec_of(intent: str) -> IntentSpec:
    try:
        return CATALOGUE[intent]
    except KeyError:
        raise IntentError(f"unknown intent {intent!r}; expected one of {sorted(CATALOGUE)}") from None


Confidence = Annotated[float, Field(ge=0.0, le=1.0)]


def _text_roles(intent: str) -> frozenset[str]:
    spec = CATALOGUE.get(intent)
    return TEXT_ROLES | frozenset(spec.grounded if spec is not None else ())


def check_data(intent: str, data: Mapping[str, object]) -> None:
    """Refuse (IntentError) a `data` whose values the contract does not allow: a null role, a role
    naming an entity (or the raw input's text) that is no string, a JSON value past the bounds.
    Which roles an intent has is make_intent's check."""
    text = _text_roles(intent)
    for role, value in data.items():
        if value is None:
            raise IntentError(f"data.{role} is null; leave a role with no value out")
        if role in text and not isinstance(value, str):
            what = "is text: a string" if role in RAW_INPUT_ROLES else "names an entity: a string (a KB id)"
            raise IntentError(f"data.{role} of {intent} {what}, not {json.dumps(value)[:80]}")
        try:
            check_json(value, f"data.{role}")
        except JsonValueError as exc:
            raise IntentError(str(exc)) from None


class Intent(BaseModel):
    """An intent as returned over REST: `data` is a JSON object (see the module's docstring for what
    its values may be); the ROS adapter serialises it."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    intent: str
    data: dict[str, JsonValue]
    source: str
    modality: str = MODALITY_SPEECH
    priority: int = Field(default=DEFAULT_PRIORITY, ge=0, le=255)
    confidence: Confidence = 1.0

    @model_validator(mode="before")
    @classmethod
    def _allowed_values(cls, values: Any) -> Any:
        # Before pydantic walks `data`: a value nested thousands deep is refused here, in one line.
        if isinstance(values, Mapping):
            intent, data = values.get("intent"), values.get("data")
            if isinstance(intent, str) and isinstance(data, Mapping):
                check_data(intent, data)
        return values

    @field_validator("modality")
    @classmethod
    def _known_modality(cls, value: str) -> str:
        if value not in MODALITIES:
            raise ValueError(f"unknown modality {value!r}; expected one of {sorted(MODALITIES)}")
        return value

    def data_json(self) -> str:
        """`data` as the JSON string of the ROS message field."""
        return json.dumps(self.data, ensure_ascii=False)


def _given(value: JsonValue | None) -> bool:
    """Whether a role has a value: null and blank text are none (D7)."""
    return value is not None and not (isinstance(value, str) and not value.strip())


def make_intent(
    intent: str,
    data: Mapping[str, JsonValue | None],
    *,
    source: str,
    confidence: float,
    modality: str = MODALITY_SPEECH,
    priority: int = DEFAULT_PRIORITY,
) -> Intent:
    """Build an intent that satisfies the contract or raise IntentError saying what is wrong.

    Null and empty roles are dropped (D7), unknown keys are refused, required roles are checked (D8),
    values are checked as `check_data` does.
    """
    spec = spec_of(intent)
    allowed = set(spec.roles) | {"agent"}
    allowed |= RAW_INPUT_ROLES if intent == RAW_USER_INPUT else {"other_data"}
    clean: dict[str, JsonValue] = {}
    for key, value in data.items():
        if key not in allowed:
            raise IntentError(f"{spec.name} has no role {key!r}; allowed: {sorted(allowed)}")
        if _given(value):
            clean[key] = value
    missing = [role for role in spec.required if role not in clean]
    if missing:
        raise IntentError(f"{spec.name} is missing required role(s) {missing}")
    if not source:
        raise IntentError("an intent needs a source (the speaker's id or a source constant)")
    check_data(intent, clean)
    return Intent(
        intent=intent,
        data=clean,
        source=source,
        modality=modality,
        priority=priority,
        confidence=confidence,
    )


def raw_user_input(text: str, *, source: str, locale: str | None = None) -> Intent:
    """The `__raw_user_input__` fallback (D4): data from a serialiser, never string concatenation."""
    data: dict[str, JsonValue] = {"input": text}
    if locale:
        data["locale"] = locale
    return Intent(intent=RAW_USER_INPUT, data=data, source=source or UNKNOWN, confidence=1.0)
