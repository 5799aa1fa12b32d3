"""The scene over REST (scene-compat): read it, replace it (simulator SVG or JSON), create, move or
remove one entity. Every change answers with the fact difference it applied to the KB."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, Body, Request
from pydantic import BaseModel, ConfigDict, Field
from starlette.concurrency import run_in_threadpool

from api.deps import ReadAccess, WorldDep, WriteAccess
from api.errors import ApiError
from scene.svg import load_svg
from scene.sync import entity_from_json, scene_from_json, scene_to_json

router = APIRouter(prefix="/scene", tags=["scene"])
SVG_TYPES = ("image/svg+xml",)
JSON_TYPES = ("application/json",)


class FactDiff(BaseModel):
    added: list[str] = Field(description="statements asserted by the change")
    removed: list[str] = Field(description="statements retracted by the change")


class EntityBody(BaseModel):
    """One entity; position and heading in the robot's frame (REP-103: x forward, y left)."""

    model_config = ConfigDict(extra="forbid")
    kind: str = Field("object", description="object, furniture, person or zone")
    cls: str | None = Field(None, alias="class", description="class CURIE, e.g. dbr:Cup (default by kind)")
    label: str | None = Field(None, description='display name, e.g. "red cup"')
    x: float = Field(description="metres forward of the robot")
    y: float = Field(description="metres to the robot's left")
    heading: float = Field(0.0, description="radians, counter-clockwise from the robot's x axis")
    width: float | None = Field(None, gt=0, description="metres along the heading")
    depth: float | None = Field(None, gt=0, description="metres across the heading")
    z: int | None = Field(None, description="stacking level (zones -100, things 0, agents 10)")


@router.get("", dependencies=[ReadAccess])
async def get_scene(world: WorldDep) -> dict[str, Any]:
    """The entities (with each person's engagement level) and the scene's policies."""
    return await run_in_threadpool(scene_to_json, world.sync)


@router.put("", dependencies=[WriteAccess], openapi_extra={"requestBody": {"required": True, "content": {
    "image/svg+xml": {"schema": {"type": "string"}},
    "application/json": {"schema": {"type": "object", "properties": {"entities": {"type": "array"}}}}}}})
async def put_scene(request: Request, world: WorldDep) -> FactDiff:
    """Replace the scene: the simulator's SVG environment, or ``{"entities": [...]}``."""
    media = request.headers.get("content-type", "").split(";")[0].strip().lower()
    data = await request.body()
    if media in SVG_TYPES:
        entities = await run_in_threadpool(load_svg, data)
    elif media in JSON_TYPES:
        entities = scene_from_json(data)
    else:
        raise ApiError(415, "unsupported_media_type", "send the scene as image/svg+xml or application/json",
                       {"accepted": [*SVG_TYPES, *JSON_TYPES]})
    diff = await run_in_threadpool(world.replace, entities)
    return FactDiff(**diff.as_dict())


@router.put("/entities/{entity_id}", dependencies=[WriteAccess])
async def put_entity(entity_id: str, body: Annotated[EntityBody, Body()], world: WorldDep) -> FactDiff:
    """Create or move one entity."""
    data = body.model_dump(by_alias=True, exclude_none=True)
    entity = entity_from_json({"id": entity_id, **data})
    diff = await run_in_threadpool(world.put, entity)
    return FactDiff(**diff.as_dict())


@router.delete("/entities/{entity_id}", dependencies=[WriteAccess])
async def delete_entity(entity_id: str, world: WorldDep) -> FactDiff:
    """Remove one entity and every fact about it (what it saw, where it was)."""
    if entity_id not in world.sync.scene:
        raise ApiError(404, "not_found", f"no entity {entity_id!r} in the scene")
    diff = await run_in_threadpool(world.remove, entity_id)
    return FactDiff(**diff.as_dict())
