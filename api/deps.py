"""FastAPI dependencies (Annotated): the service's parts and the access checks."""

from __future__ import annotations

from typing import Annotated

from fastapi import Depends, Query
from fastapi.security import HTTPAuthorizationCredentials
from fastapi.security.utils import get_authorization_scheme_param
from starlette.requests import HTTPConnection

from api.auth import authorise, bearer
from api.errors import ApiError
from api.services import Services
from api.settings import Settings
from api.subscriptions import EventHub
from kb.protocol import KnowledgeBase
from scene.world import World


async def get_services(conn: HTTPConnection) -> Services:
    services: Services = conn.app.state.services
    return services


ServicesDep = Annotated[Services, Depends(get_services)]


async def get_kb(services: ServicesDep) -> KnowledgeBase:
    return services.kb


async def get_world(services: ServicesDep) -> World:
    if services.world is None:  # a reader forwards /scene to the writer before routing
        raise ApiError(503, "scene_elsewhere", "the scene is kept by the writer service")
    return services.world


async def get_settings(services: ServicesDep) -> Settings:
    return services.settings


async def get_hub(services: ServicesDep) -> EventHub:
    return services.hub


KbDep = Annotated[KnowledgeBase, Depends(get_kb)]
WorldDep = Annotated[World, Depends(get_world)]
SettingsDep = Annotated[Settings, Depends(get_settings)]
HubDep = Annotated[EventHub, Depends(get_hub)]
Credentials = Annotated[HTTPAuthorizationCredentials | None, Depends(bearer)]


def presented_token(connection: HTTPConnection) -> str | None:
    """The bearer token of a request, if any, for a public route that tells more to a reader: unlike
    ``Credentials`` it declares no security scheme, so the API description says the route is open."""
    scheme, token = get_authorization_scheme_param(connection.headers.get("authorization"))
    return token if scheme.lower() == "bearer" and token else None


PresentedToken = Annotated[str | None, Depends(presented_token)]


async def require_read(settings: SettingsDep, credentials: Credentials) -> None:
    authorise(settings, credentials.credentials if credentials else None, write=False)


async def require_write(settings: SettingsDep, credentials: Credentials) -> None:
    authorise(settings, credentials.credentials if credentials else None, write=True)


async def require_read_stream(settings: SettingsDep, credentials: Credentials,
                        access_token: Annotated[str | None, Query(
                            description="the token, for clients that cannot send headers")] = None,
                        ) -> None:
    presented = credentials.credentials if credentials else access_token
    authorise(settings, presented, write=False)


ReadAccess = Depends(require_read)
StreamReadAccess = Depends(require_read_stream)
WriteAccess = Depends(require_write)
