"""Dialogues over REST (chatbot_msgs 3.0.0 shapes, dialogue-compat §2): start, interact, end."""

from __future__ import annotations

from functools import partial
from typing import Annotated, Any

from fastapi import APIRouter, Depends, Request, Response
from pydantic import AfterValidator, BaseModel, ConfigDict, Field

from api.deps import ServicesDep, WriteAccess
from api.errors import ApiError
from api.limits import check_count, check_length
from api.turnevents import EVENT_STREAM, turn_events, wants_events
from dialogue.engine import TurnResult
from dialogue.history import Utterance
from dialogue.intents import Intent
from dialogue.sessions import DEFAULT_ROLE, DialogueManager, SessionError, check_utterance

router = APIRouter(prefix="/dialogues", tags=["dialogue"])


class Role(BaseModel):
    model_config = ConfigDict(extra="forbid")
    name: str = DEFAULT_ROLE
    configuration: str = Field(default="{}", description="opaque JSON string, per chatbot_msgs/DialogueRole")


class StartRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    role: Role | None = None
    locale: str | None = Field(default=None, description="ll_CC, e.g. en_GB")


class Started(BaseModel):
    dialogue_id: str


class Turn(BaseModel):
    model_config = ConfigDict(extra="forbid")
    speaker: str
    text: str


class InteractionRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    user_id: str = Field(min_length=1, description="the speaker's person id, or __system__ / __assistant__")
    input: Annotated[str, AfterValidator(check_utterance)] = Field(description="what was said; not blank")
    response_expected: bool = True
    locale: str | None = None
    history: list[Turn] | None = Field(default=None, description="4.0.0 shape: replaces the stored history")


class InteractionResponse(BaseModel):
    response: str
    intents: list[Intent]
    error_msg: str


async def get_dialogues(services: ServicesDep) -> DialogueManager:
    return services.dialogues


Dialogues = Annotated[DialogueManager, Depends(get_dialogues)]


async def _existing(dialogues: DialogueManager, dialogue_id: str) -> None:
    try:
        await dialogues.get_async(dialogue_id)
    except SessionError as exc:
        raise ApiError(404, "unknown_dialogue", str(exc)) from exc


@router.post("", status_code=201, dependencies=[WriteAccess])
async def start(dialogues: Dialogues, body: StartRequest | None = None) -> Started:
    """Start a dialogue with a role; the id is a new UUID (``default`` always exists)."""
    request = body or StartRequest()
    role = request.role or Role()
    dialogue = await dialogues.start_async(role.name, request.locale, role.configuration)
    return Started(dialogue_id=dialogue.id)


def _response(result: TurnResult) -> InteractionResponse:
    return InteractionResponse(response=result.response, intents=list(result.intents),
                               error_msg=result.error_msg)


def _body(result: TurnResult) -> dict[str, Any]:
    return _response(result).model_dump(mode="json", by_alias=True)  # as FastAPI serialises it


@router.post("/{dialogue_id}/interactions", dependencies=[WriteAccess], response_model=InteractionResponse,
             responses={200: {"content": {EVENT_STREAM: {"schema": {"type": "string"}}}, "description":
                              "with `Accept: text/event-stream`: `event: ack` ({\"verbal_ack\"}) when the "
                              "model's reply is ready early, then `event: response` (the JSON answer)"}})
async def interact(dialogue_id: str, body: InteractionRequest, dialogues: Dialogues,
                   services: ServicesDep, request: Request) -> InteractionResponse | Response:
    """One DialogueInteraction: the reply and the validated intents, most relevant first."""
    check_length(body.input, services.settings.limits.max_input_chars, "input")
    history = None
    if body.history is not None:
        check_count(body.history, services.settings.limits.max_history_turns, "history_turns")
        history = [Utterance(turn.speaker, turn.text) for turn in body.history]
    run = partial(dialogues.interact, body.user_id, body.input, dialogue_id=dialogue_id, locale=body.locale,
                  response_expected=body.response_expected, history=history)
    try:  # the turn reads the dialogue once: an unknown one is refused, an unreadable store answered
        if wants_events(request.headers.get("accept")):
            return await turn_events(run, _body)
        return _response(await run())
    except SessionError as exc:
        raise ApiError(404, "unknown_dialogue", str(exc)) from exc


@router.delete("/{dialogue_id}", status_code=204, dependencies=[WriteAccess])
async def end(dialogue_id: str, dialogues: Dialogues) -> Response:
    """Forget a dialogue (``default`` is only cleared)."""
    await _existing(dialogues, dialogue_id)
    await dialogues.end_async(dialogue_id)
    return Response(status_code=204)
