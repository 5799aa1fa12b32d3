"""Dialogues over REST (chatbot_msgs shapes, dialogue-compat §2): start, interact, where it is, end.

An interaction is the 3.0 incremental shape (`user_id`, `input`; the service keeps the history) or
the 4.0 stateless one (`role`, `history`, `summary`: the caller keeps the history; the last
utterance of `history` is the input when `input` is not given). See `dialogue.sessions.manager`.
"""

from __future__ import annotations

import re
from functools import partial
from typing import Annotated, Any

from fastapi import APIRouter, Depends, Request, Response
from pydantic import AfterValidator, BaseModel, ConfigDict, Field, model_validator
from starlette.requests import HTTPConnection

from api.deps import ReadAccess, WriteAccess, services_of
from api.errors import ApiError
from api.limits import check_count, check_length
from api.turnevents import EVENT_STREAM, turn_events, wants_events
from dialogue.engine import TurnResult
from dialogue.history import ASSISTANT_USER_ID, Utterance
from dialogue.intents import Intent
from dialogue.locales import normalise_locale
from dialogue.sessions.manager import (
    DEFAULT_ROLE,
    DialogueExists,
    DialogueManager,
    DialogueState,
    UnknownDialogue,
)
from dialogue.sessions.rolestate import Progress, Status

router = APIRouter(prefix="/dialogues", tags=["dialogue"])
#: The id of the turn's trace, in the interaction's answer.
TURN_HEADER = "X-Situated-Turn"


class Role(BaseModel):
    model_config = ConfigDict(extra="forbid")
    name: str = DEFAULT_ROLE
    configuration: str = Field(default="{}", description="opaque JSON string, per chatbot_msgs/DialogueRole")


def _locale(value: str | None) -> str | None:
    """`ll_CC`; "" is no locale (chatbot_msgs' locale is optional, and ROS sends an unset string as "")."""
    return normalise_locale(value) if value else None


Locale = Annotated[str | None, AfterValidator(_locale)]
#: A dialogue id a caller chooses is a path segment of every route of the dialogue (a UUID fits).
_CHOSEN_ID = re.compile(r"[A-Za-z0-9][A-Za-z0-9._:-]{0,127}")


def _chosen_id(value: str) -> str:
    if not _CHOSEN_ID.fullmatch(value):
        shown = value if len(value) <= 40 else f"{value[:40]}..."
        raise ValueError(f"dialogue_id {shown!r} cannot be a dialogue's id: 1 to 128 characters, letters, "
                         "digits, '.', '_', ':' or '-', the first a letter or a digit (a UUID fits)")
    return value


class StartRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    role: Role | None = None
    locale: Locale = Field(default=None, description="ll_CC, e.g. en_GB (empty: none)")
    dialogue_id: Annotated[str, AfterValidator(_chosen_id)] | None = Field(
        default=None, description="the dialogue's id, chosen by the caller (a ROS Dialogue goal's UUID); "
        "default: a new UUID. An id in use is refused (409 dialogue_exists)")


class Started(BaseModel):
    dialogue_id: str
    response: str | None = Field(default=None, description="the robot's opening line (the ask role's "
                                 "question), to say; absent when the role has none")


class Turn(BaseModel):
    model_config = ConfigDict(extra="forbid")
    speaker: str = Field(min_length=1, description="a person id, or __system__ / __assistant__")
    text: str


class InteractionRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    user_id: str | None = Field(default=None, min_length=1,
                                description="the speaker's person id, or __system__ / __assistant__")
    input: str | None = Field(
        default=None, description="what was said (4.0: the last utterance of history when absent); empty: "
        "nothing said, so no answer and nothing recorded (a __system__ update may be empty)")
    response_expected: bool = True
    locale: Locale = None
    history: list[Turn] | None = Field(default=None, description="the dialogue so far (4.0.0 shape); "
                                       "replaces the stored history")
    role: Role | None = Field(default=None, description="4.0.0: the dialogue's role; the turn is stateless")
    summary: str | None = Field(default=None, description="4.0.0: a summary of earlier sessions")

    @model_validator(mode="after")
    def _the_input(self) -> InteractionRequest:
        """4.0: no `input`: the last utterance of `history` is the turn's input, its speaker the user."""
        if self.input is None:
            if not self.history:
                raise ValueError("input is required (or, in the 4.0 shape, a history whose last utterance "
                                 "is the input)")
            last = self.history[-1]
            if last.speaker == ASSISTANT_USER_ID:
                raise ValueError("the history ends with the robot's own utterance: nothing to answer")
            self.user_id, self.input = last.speaker, last.text
            self.history = self.history[:-1]
        elif self.user_id is None:
            raise ValueError("user_id is required with input")
        return self


class InteractionResponse(BaseModel):
    response: str
    intents: list[Intent]
    error_msg: str
    dialogue_terminal: bool | None = Field(default=None, description="the role's dialogue is over (the "
                                           "ask role: every field obtained, or cancelled); always in 4.0")
    results: str | None = Field(default=None, description="the role's results, a JSON object string (the ask "
                                "role: the fields obtained; the others are omitted)")


class DialogueStatus(BaseModel):
    """Where a dialogue is by its role: what a ROS Dialogue action's result reports when it ends."""

    dialogue_id: str
    role: str
    locale: str | None = None
    status: Status = Field(description="open; or over: done (the role obtained its results: the ask role's "
                           "form filled), cancelled (the person called it off)")
    results: str = Field(description="the role's results, a JSON object string (the ask role: the fields "
                         "obtained so far)")
    error_msg: str = Field(description="why the dialogue is over without its role done (cancelled), else "
                           "empty: the Dialogue action result's error_msg")


def _status(dialogue_id: str, role: str, locale: str | None, progress: Progress) -> DialogueStatus:
    return DialogueStatus(dialogue_id=dialogue_id, role=role, locale=locale, status=progress.status,
                          results=progress.results, error_msg=progress.error_msg)


async def get_dialogues(conn: HTTPConnection) -> DialogueManager:
    return services_of(conn).dialogues


Dialogues = Annotated[DialogueManager, Depends(get_dialogues)]


async def _existing(dialogues: DialogueManager, dialogue_id: str) -> DialogueState:
    try:
        return await dialogues.get_async(dialogue_id)
    except UnknownDialogue as exc:
        raise ApiError(404, "unknown_dialogue", str(exc)) from exc


@router.post("", status_code=201, dependencies=[WriteAccess], response_model_exclude_none=True)
async def start(dialogues: Dialogues, body: StartRequest | None = None) -> Started:
    """Start a dialogue with a role; its id is the caller's ``dialogue_id``, or a new UUID
    (``default`` always exists)."""
    request = body or StartRequest()
    role = request.role or Role()
    try:
        dialogue = await dialogues.start_async(role.name, request.locale, role.configuration,
                                               request.dialogue_id)
    except DialogueExists as exc:
        raise ApiError(409, "dialogue_exists", str(exc)) from exc
    return Started(dialogue_id=dialogue.id, response=dialogues.opening_line(dialogue) or None)


def _response(result: TurnResult) -> InteractionResponse:
    return InteractionResponse(response=result.response, intents=list(result.intents),
                               error_msg=result.error_msg, dialogue_terminal=result.dialogue_terminal,
                               results=result.results)


def _body(result: TurnResult) -> dict[str, Any]:
    # as FastAPI serialises it
    return _response(result).model_dump(mode="json", by_alias=True, exclude_none=True)


@router.post("/{dialogue_id}/interactions", dependencies=[WriteAccess], response_model=InteractionResponse,
             response_model_exclude_none=True,
             responses={200: {"content": {EVENT_STREAM: {"schema": {"type": "string"}}}, "description":
                              "with `Accept: text/event-stream`: `event: ack` ({\"verbal_ack\"}) when the "
                              "model's reply is ready early, then `event: response` (the JSON answer)"}})
async def interact(dialogue_id: str, body: InteractionRequest, request: Request,
                   response: Response) -> InteractionResponse | Response:
    """One DialogueInteraction: the reply and the validated intents, most relevant first."""
    # The service's parts read off the app's state rather than as dependencies: FastAPI solves each
    # dependency anew per request, a tenth of this route's own work when the rules answer.
    services = services_of(request)
    dialogues = services.dialogues
    assert body.input is not None and body.user_id is not None  # the request model's validator
    check_length(body.input, services.settings.limits.max_input_chars, "input")
    check_length(body.summary or "", services.settings.limits.max_input_chars, "summary")
    history = None
    if body.history is not None:
        check_count(body.history, services.settings.limits.max_history_turns, "history_turns")
        history = [Utterance(turn.speaker, turn.text) for turn in body.history]
    role, configuration = (None, "{}") if body.role is None else (body.role.name, body.role.configuration)
    run = partial(dialogues.interact, body.user_id, body.input, dialogue_id=dialogue_id, locale=body.locale,
                  response_expected=body.response_expected, history=history, summary=body.summary, role=role,
                  configuration=configuration)
    # The turn reads the dialogue once: an unknown one is refused (404), an unreadable store answered;
    # other refusals (bad text, a bad role configuration) are the request's (400).
    try:
        if wants_events(request.headers.get("accept")):
            return await turn_events(run, _body)
        result = await run()
        if result.trace is not None:  # where to read this turn's trace (GET /dialogues/{id}/turns)
            response.headers[TURN_HEADER] = result.trace.id
        return _response(result)
    except UnknownDialogue as exc:
        raise ApiError(404, "unknown_dialogue", str(exc)) from exc


@router.get("/{dialogue_id}", dependencies=[ReadAccess], response_model_exclude_none=True)
async def status(dialogue_id: str, dialogues: Dialogues) -> DialogueStatus:
    """Where the dialogue is: open, or over (done, cancelled) with its role's results."""
    state = await _existing(dialogues, dialogue_id)
    return _status(state.id, state.role, state.locale, dialogues.progress(state))


@router.delete("/{dialogue_id}", dependencies=[WriteAccess], response_model_exclude_none=True)
async def end(dialogue_id: str, dialogues: Dialogues) -> DialogueStatus:
    """Forget a dialogue (``default`` is only cleared); the answer is where it was as it ended (its
    results; ``open``: ended before its role was done)."""
    state = await _existing(dialogues, dialogue_id)
    try:
        progress = await dialogues.end_async(dialogue_id)
    except UnknownDialogue as exc:  # ended meanwhile
        raise ApiError(404, "unknown_dialogue", str(exc)) from exc
    return _status(state.id, state.role, state.locale, progress)
