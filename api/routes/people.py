"""What the robot keeps of each person across dialogues (dialogue.memory.people)."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter
from starlette.concurrency import run_in_threadpool

from api.deps import ReadAccess, ServicesDep
from dialogue.memory.people import People

router = APIRouter(prefix="/people", tags=["dialogue"])


@router.get("/{person_id}/memory", dependencies=[ReadAccess])
async def memory(person_id: str, services: ServicesDep) -> dict[str, Any]:
    """``last_spoke`` and ``summary`` of earlier dialogues; ``told``: the facts the person told
    that the robot adopted, ``told_about``: those others told about them; each with ``by``, ``at``
    (when) and ``words``."""
    return await run_in_threadpool(People(services.kb).about, person_id)
