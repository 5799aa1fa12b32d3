"""The trace of each dialogue turn: ``GET /dialogues/{id}/turns`` (dialogue.trace), most recent first,
with the service's token (and any URL credential) taken out."""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, Query
from pydantic import BaseModel

from api.deps import ReadAccess, ServicesDep
from api.errors import ApiError
from dialogue.errors import UnknownDialogue
from dialogue.trace import TurnTrace, redacted

router = APIRouter(prefix="/dialogues", tags=["dialogue"])


class Turns(BaseModel):
    dialogue_id: str
    turns: list[TurnTrace]


@router.get("/{dialogue_id}/turns", dependencies=[ReadAccess], response_model_by_alias=True)
async def turns(dialogue_id: str, services: ServicesDep,
                limit: Annotated[int, Query(ge=1, le=100, description="most recent turns to return")] = 20,
                ) -> Turns:
    """What each recent turn of the dialogue did: the snapshot summary, the backend that answered, the
    prompt messages and JSON schema sent, the raw answers, validation errors and repair, the resolved
    intents, the role's notes and the time of each stage. Kept in memory, bounded (20 turns per
    dialogue, the most recently used dialogues), by the process that ran the turns."""
    dialogues = services.dialogues
    kept = dialogues.traces.recent(dialogue_id, limit)
    if kept is None:
        try:  # a dialogue with no turn yet has no trace; an unknown one is an error
            await dialogues.get_async(dialogue_id)
        except UnknownDialogue as exc:
            raise ApiError(404, "unknown_dialogue", f"{exc} (and no turn of it is traced)") from exc
        kept = []
    token = services.settings.token.get_secret_value() if services.settings.token else ""
    return Turns(dialogue_id=dialogue_id, turns=[redacted(trace, [token]) for trace in kept])
