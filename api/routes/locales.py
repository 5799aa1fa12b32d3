"""``GET /locales``: the locales the service answers in (i18n_msgs ``GetLocales``; empty: any)."""

from __future__ import annotations

from fastapi import APIRouter
from pydantic import BaseModel, Field

from api.deps import ReadAccess, ServicesDep
from dialogue.locales import RULES_LANGUAGES, supported_locales

router = APIRouter(tags=["dialogue"])


class Locales(BaseModel):
    locales: list[str] = Field(description="ll_CC locales the dialogues answer in; empty: any (a model "
                               "backend is told to reply in the dialogue's language)")
    rules: list[str] = Field(description="the languages the offline rules understand; a turn in another "
                             "language goes to the model (hybrid) or is answered with __raw_user_input__")


@router.get("/locales", dependencies=[ReadAccess])
async def locales(services: ServicesDep) -> Locales:
    model = services.dialogues.engine.model
    supported = supported_locales(reads_prompts=model.llm is not None)
    return Locales(locales=supported, rules=list(RULES_LANGUAGES))
