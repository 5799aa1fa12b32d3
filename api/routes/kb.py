"""The KB over REST (kb-compat §3): queries, revisions, details, lookup, load/export, clear."""

from __future__ import annotations

from typing import Annotated, Any, Literal

from fastapi import APIRouter, Query, Request, Response
from pydantic import BaseModel, ConfigDict, Field
from starlette.concurrency import run_in_threadpool

from api.deps import KbDep, ReadAccess, ServicesDep, SettingsDep, WriteAccess
from api.errors import ApiError
from api.limits import check_count
from api.negotiation import RDF_UPLOAD_TYPES, negotiate, upload_format
from api.settings import Settings
from kb.arguments import Changes
from kb.formats import EXPORTS
from kb.protocol import KnowledgeBase

router = APIRouter(prefix="/kb", tags=["kb"])

Models = Annotated[list[str] | None, Query(description="models to use; default: the robot's own")]
RDF_EXPORT = {fmt.media_type: fmt.name for fmt in EXPORTS}


class QueryRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    patterns: list[str] = Field(min_length=1, description='e.g. ["?o isOn table_1", "?o rdf:type dbr:Cup"]')
    vars: list[str] | None = Field(default=None, description='variables to return, e.g. ["?o"]')
    models: list[str] | None = None


class ReviseRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    statements: list[str] = Field(min_length=1, description='e.g. ["cup_1 isOn table_1"]')
    method: Literal["add", "update", "retract", "remove", "safe_add", "safe_update", "revision"]
    models: list[str] | None = None
    lifespan: float | None = Field(default=None, ge=0, description="seconds until expiry; 0: never")


class ApplyRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    add: list[str] = Field(default_factory=list, description='e.g. ["cup_1 isOn shelf_1"]')
    remove: list[str] = Field(default_factory=list, description='e.g. ["cup_1 isOn table_1"]')
    models: list[str] | None = None
    lifespan: float | None = Field(default=None, ge=0, description="seconds until the added facts expire")


class ModelChanges(BaseModel):
    model_config = ConfigDict(extra="forbid")
    add: list[str] = Field(default_factory=list, description='e.g. ["mug_1 belongsTo person_bob"]')
    remove: list[str] = Field(default_factory=list)


class ApplyModelsRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    changes: dict[str, ModelChanges] = Field(min_length=1, description="per model name, its own changes: "
                                             '{"person_bob": {"add": [...]}, "default": {"add": [...]}}')
    lifespan: float | None = Field(default=None, ge=0, description="seconds until the added facts expire")


class ClearRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    keep_defaults: bool = Field(True, description="keep the default ontology")


class Revision(BaseModel):
    revision: int = Field(description="the KB revision after the change")


class Revised(Revision):
    removed: int | None = Field(None, description="a retraction: the number of asserted triples it "
                                "removed (a pattern may match many; facts only inferred stay)")


@router.post("/query", dependencies=[ReadAccess])
async def query(body: QueryRequest, kb: KbDep, settings: SettingsDep) -> list[Any]:
    """Rows of bindings for a conjunction of patterns (kb-compat §3.2)."""
    check_count(body.patterns, settings.limits.max_patterns, "patterns")
    check_count(body.models or [], settings.limits.max_models, "models")
    return await _find(kb, settings, body.patterns, body.vars, body.models)


async def _find(kb: KnowledgeBase, settings: Settings, patterns: list[str], vars: list[str] | None,
                models: list[str] | None) -> list[Any]:
    limits = settings.limits
    return await run_in_threadpool(lambda: kb.find(patterns, vars, models, max_rows=limits.max_rows,
                                                   timeout=limits.query_timeout))


@router.get("/query", dependencies=[ReadAccess])
async def query_get(kb: KbDep, settings: SettingsDep,
                    pattern: Annotated[list[str], Query(min_length=1, description="a pattern (repeatable)")],
                    models: Models = None) -> list[Any]:
    """Rows of bindings for ``?pattern=...`` (repeat it for a conjunction)."""
    check_count(pattern, settings.limits.max_patterns, "patterns")
    check_count(models or [], settings.limits.max_models, "models")
    return await _find(kb, settings, pattern, None, models)


@router.post("/revise", dependencies=[WriteAccess])
async def revise(body: ReviseRequest, kb: KbDep, settings: SettingsDep) -> Revised:
    """Add, update or retract statements as one batch: all or nothing."""
    check_count(body.statements, settings.limits.max_statements, "statements")
    check_count(body.models or [], settings.limits.max_models, "models")
    policy = {"method": body.method, "models": body.models, "lifespan": body.lifespan or 0}
    removed = await run_in_threadpool(kb.revise, body.statements, policy)
    return Revised(revision=kb.revision, removed=removed)


@router.post("/apply", dependencies=[WriteAccess])
async def apply(body: ApplyRequest, kb: KbDep, settings: SettingsDep) -> Revision:
    """Retract ``remove`` and assert ``add`` (ground statements) as ONE batch: one revision, one
    reasoning pass, one round of events: a perception tick. ``add`` replaces a functional
    property's old value as ``update`` does."""
    check_count([*body.add, *body.remove], settings.limits.max_statements, "statements")
    check_count(body.models or [], settings.limits.max_models, "models")
    await run_in_threadpool(kb.apply, body.add, body.remove, body.models, body.lifespan or 0)
    return Revision(revision=kb.revision)


@router.post("/apply_models", dependencies=[WriteAccess])
async def apply_models(body: ApplyModelsRequest, kb: KbDep, settings: SettingsDep) -> Revision:
    """Each model's own ``remove`` retracted and ``add`` asserted, all as ONE batch: one revision;
    refused, no model changed (a person's belief and the robot's adoption of it, together)."""
    check_count([s for c in body.changes.values() for s in (*c.add, *c.remove)],
                settings.limits.max_statements, "statements")
    check_count(list(body.changes), settings.limits.max_models, "models")
    changes: dict[str, Changes] = {n: {"add": c.add, "remove": c.remove} for n, c in body.changes.items()}
    await run_in_threadpool(kb.apply_models, changes, body.lifespan or 0)
    return Revision(revision=kb.revision)


@router.get("/details/{term:path}", dependencies=[ReadAccess])
async def details(term: str, kb: KbDep, models: Models = None,
                  origin: Annotated[bool, Query(description="add 'asserted': a flag per relation, "
                                                "false when it is only inferred")] = False) -> dict[str, Any]:
    """``{"id", "label", "type", "attributes", "relations"}`` (kb-compat §3.3)."""
    return await run_in_threadpool(kb.details, term, models, origin)


@router.get("/label/{term:path}", dependencies=[ReadAccess])
async def label(term: str, kb: KbDep, lang: str | None = None, models: Models = None) -> str:
    """The term's label in ``lang`` (else the default label), as a JSON string."""
    return await run_in_threadpool(kb.label, term, lang, models)


@router.get("/lookup", dependencies=[ReadAccess])
async def lookup(q: Annotated[str, Query(min_length=1)], kb: KbDep, models: Models = None) -> list[list[str]]:
    """``[[name, type], ...]``: exact matches first, then approximate ones."""
    return await run_in_threadpool(kb.lookup, q, models)


@router.get("/about/{term:path}", dependencies=[ReadAccess])
async def about(term: str, kb: KbDep, models: Models = None) -> list[list[Any]]:
    """``[[s, p, o], ...]`` where the term appears."""
    return await run_in_threadpool(kb.about, term, models)


@router.get("/classesof/{term:path}", dependencies=[ReadAccess])
async def classesof(term: str, kb: KbDep, direct: bool = False, models: Models = None) -> list[str]:
    """The term's classes (asserted only with ``direct=true``)."""
    return await run_in_threadpool(kb.classesof, term, direct, models)


@router.post("/load", dependencies=[WriteAccess], openapi_extra={
    "requestBody": {"required": True,
                    "content": {t: {"schema": {"type": "string"}} for t in RDF_UPLOAD_TYPES}}})
async def load(request: Request, kb: KbDep, settings: SettingsDep, models: Models = None,
               format: Annotated[str | None, Query(description="RDF format (a name or media type), "
                                                   "else by Content-Type")] = None,
               ) -> Revision:
    """Add an RDF document sent as the body (Turtle, RDF/XML, JSON-LD, N-Triples, N3, TriG,
    N-Quads, TriX) as one batch."""
    fmt = upload_format(format, request.headers.get("content-type"))
    check_count(models or [], settings.limits.max_models, "models")
    data = await request.body()
    if not data.strip():
        raise ApiError(422, "empty_document", "the request body is empty; send an RDF document")
    await run_in_threadpool(kb.load_data, data, fmt, models)
    return Revision(revision=kb.revision)


@router.get("/export", dependencies=[ReadAccess], response_class=Response, responses={
    200: {"content": {t: {} for t in RDF_EXPORT}, "description": "the model's triples"}})
async def export(request: Request, kb: KbDep, model: str | None = None, inferred: bool = False) -> Response:
    """A model's asserted (or with ``inferred=true``, materialised) triples, format by Accept."""
    media = negotiate(request.headers.get("accept"), list(RDF_EXPORT))
    data = await run_in_threadpool(kb.export, RDF_EXPORT[media], model, inferred)
    return Response(data, media_type=media)


@router.post("/clear", dependencies=[WriteAccess])
async def clear(services: ServicesDep, body: ClearRequest | None = None) -> Revision:
    """Drop every model's facts (the default ontology stays unless ``keep_defaults`` is false);
    the scene's facts are asserted again, since the scene is still there."""
    await run_in_threadpool(services.clear, body.keep_defaults if body else True)
    return Revision(revision=services.kb.revision)
