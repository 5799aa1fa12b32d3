"""The SPARQL 1.1 Protocol endpoint: GET ?query=, POST form (query= or update=), POST
application/sparql-query and application/sparql-update. Updates need ``sparql_update`` and write
access."""

from __future__ import annotations

from typing import Annotated
from urllib.parse import parse_qs

from fastapi import APIRouter, Query, Request, Response
from starlette.concurrency import run_in_threadpool

from api import sparql
from api.auth import authorise
from api.deps import Credentials, KbDep, ReadAccess, SettingsDep
from api.errors import ApiError
from api.settings import Settings
from kb.protocol import KnowledgeBase

router = APIRouter(tags=["sparql"])
_DATASET_PARAMS = ("default-graph-uri", "named-graph-uri", "using-graph-uri", "using-named-graph-uri")
Model = Annotated[str | None, Query(description="the KB model to query (situated extension)")]


def _reject_datasets(params: dict[str, list[str]]) -> None:
    used = [p for p in _DATASET_PARAMS if p in params]
    if used:
        raise ApiError(400, "unsupported_dataset",
                       f"{', '.join(used)} is not supported: each KB model is one dataset; use ?model=")


async def _query(kb: KnowledgeBase, settings: Settings, text: str, request: Request,
                 model: str | None) -> Response:
    media, body = await run_in_threadpool(sparql.answer, kb, text, request.headers.get("accept"), model,
                                          settings.limits)
    return Response(body, media_type=media)


async def _update(kb: KnowledgeBase, settings: Settings, text: str, token: str | None,
                  model: str | None) -> Response:
    if not settings.sparql_update:
        raise ApiError(403, "sparql_update_disabled",
                       "SPARQL Update is disabled on this service (settings: sparql_update)")
    authorise(settings, token, write=True)
    await run_in_threadpool(sparql.apply_update, kb, text, model)
    return Response(status_code=204)


@router.get("/sparql", dependencies=[ReadAccess], response_class=Response)
async def sparql_get(request: Request, kb: KbDep, settings: SettingsDep, query: str | None = None,
                     model: Model = None) -> Response:
    """A read-only query in ``?query=``; the result format follows the Accept header."""
    _reject_datasets(parse_qs(request.url.query))
    if not query:
        raise ApiError(400, "missing_query", "give the SPARQL query in the 'query' parameter")
    return await _query(kb, settings, query, request, model)


_TEXT = {"schema": {"type": "string"}}
_FORM = {"schema": {"type": "object", "properties": {"query": _TEXT["schema"], "update": _TEXT["schema"]}}}


@router.post("/sparql", dependencies=[ReadAccess], response_class=Response, openapi_extra={
    "requestBody": {"content": {"application/sparql-query": _TEXT, "application/sparql-update": _TEXT,
                                "application/x-www-form-urlencoded": _FORM}}})
async def sparql_post(request: Request, kb: KbDep, settings: SettingsDep, credentials: Credentials,
                      model: Model = None) -> Response:
    """A query or an update, as a form (``query=`` / ``update=``) or a direct body."""
    _reject_datasets(parse_qs(request.url.query))
    token = credentials.credentials if credentials else None
    media = request.headers.get("content-type", "").split(";")[0].strip().lower()
    body = await request.body()
    try:
        text = body.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ApiError(400, "invalid_encoding", "the request body must be UTF-8") from exc
    if media == "application/sparql-query":
        return await _query(kb, settings, text, request, model)
    if media == "application/sparql-update":
        return await _update(kb, settings, text, token, model)
    if media != "application/x-www-form-urlencoded":
        raise ApiError(415, "unsupported_media_type",
                       "send application/x-www-form-urlencoded, application/sparql-query or "
                       "application/sparql-update")
    form = parse_qs(text, keep_blank_values=True)
    _reject_datasets(form)
    queries, updates = form.get("query", []), form.get("update", [])
    if len(queries) + len(updates) != 1:
        raise ApiError(400, "missing_query", "give exactly one 'query' or one 'update' form field")
    if queries:
        return await _query(kb, settings, queries[0], request, model)
    return await _update(kb, settings, updates[0], token, model)
