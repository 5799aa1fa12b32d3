"""Rasa-compatible facade: the REST channel webhook and ``/model/parse``, so a client written for
``rasa run`` (port 5005) works when pointed at this service. Both run a dialogue turn (which spends
model requests under a model backend), so both need the token as an interaction does; it may also
be given as ``?token=`` as Rasa's HTTP API does."""

from __future__ import annotations

import logging
from typing import Annotated, Any

from fastapi import APIRouter, Depends, Query
from pydantic import AfterValidator, BaseModel, ConfigDict, Field
from starlette.concurrency import run_in_threadpool

from api import rasa
from api.auth import authorise
from api.deps import Credentials, ServicesDep, SettingsDep
from api.errors import ApiError
from api.limits import check_length
from dialogue.engine import TurnResult
from dialogue.sessions.manager import DialogueManager, SessionError, check_utterance, said_nothing
from kb import KbError
from kb.protocol import KnowledgeBase

router = APIRouter(tags=["rasa"])
log = logging.getLogger("situated.api")
UNKNOWN_AGENT = "__unknown_agent__"
Token = Annotated[str | None, Query(description="the service token (Rasa style)")]


def _rasa_access(write: bool) -> Any:
    async def check(settings: SettingsDep, credentials: Credentials, token: Token = None) -> None:
        authorise(settings, credentials.credentials if credentials else token, write=write)
    return Depends(check)


class WebhookMessage(BaseModel):
    model_config = ConfigDict(extra="ignore")
    sender: str = Field(min_length=1, description="the conversation id; also the user id")
    message: str = Field(description="what was said; blank: nothing said, answered [] as Rasa does")
    metadata: dict[str, Any] | None = None
    input_channel: str | None = None


class ParseRequest(BaseModel):
    model_config = ConfigDict(extra="ignore")
    text: Annotated[str, AfterValidator(check_utterance)] = Field(description="the utterance; not blank")
    message_id: str | None = None
    sender: str | None = Field(default=None, min_length=1, description="who said it (as the webhook's "
                               "sender: a person id); \"me\" is them. Rasa's own request has no speaker")


async def _ensure_dialogue(dialogues: DialogueManager, key: str) -> None:
    try:
        await dialogues.get_async(key)
    except SessionError:
        try:
            await dialogues.start_async(dialogue_id=key)
        except SessionError:  # started concurrently by another request
            await dialogues.get_async(key)


@router.get("/webhooks/rest/")
async def webhook_health() -> dict[str, str]:
    return {"status": "ok"}


@router.post("/webhooks/rest/webhook", dependencies=[_rasa_access(write=True)])
async def webhook(body: WebhookMessage, services: ServicesDep,
                  stream: bool = False) -> list[dict[str, Any]]:
    """``[{"recipient_id", "text", "custom": {"intents": [...]}}]``; the sender is the user id."""
    if stream:
        raise ApiError(400, "unsupported", "stream=true is not supported; omit it")
    check_length(body.message, services.settings.limits.max_input_chars, "message")
    await services.dialogues.engine.check_speaker(body.sender, "sender")  # before its dialogue is made
    if said_nothing(body.sender, body.message):  # no answer, nothing recorded, no dialogue made
        return []
    key = rasa.dialogue_key(body.sender)
    await _ensure_dialogue(services.dialogues, key)
    result: TurnResult = await services.dialogues.interact(body.sender, body.message, dialogue_id=key)
    if result.error_msg:
        log.warning("rasa webhook turn for %s: %s", body.sender, result.error_msg)
    return rasa.webhook_messages(body.sender, result.response, result.intents)


def _labeller(kb: KnowledgeBase) -> Any:
    def label(term: str) -> str:
        try:
            return str(kb.label(term))
        except KbError:
            return term
    return label


@router.post("/model/parse", dependencies=[_rasa_access(write=True)])
async def parse(body: ParseRequest, services: ServicesDep) -> dict[str, Any]:
    """NLU only: the turn's intents as Rasa's parse result; nothing is recorded in a dialogue. The
    ``sender``, when given, is the speaker (checked as any speaker: an id naming what is no person is
    refused; one the KB does not know becomes a person of it, as the webhook's sender does)."""
    check_length(body.text, services.settings.limits.max_input_chars, "text")
    speaker = body.sender or UNKNOWN_AGENT
    await services.dialogues.engine.check_speaker(speaker, "sender")
    result = await services.dialogues.engine.turn(body.text, speaker=speaker)
    label = _labeller(services.kb)
    return await run_in_threadpool(rasa.parse_result, body.text, result.intents, label)
