"""FastAPI dependencies (Annotated): the service's parts and the access checks."""

from __future__ import annotations

from typing import Annotated

from fastapi import Depends, Query
from fastapi.security import HTTPAuthorizationCredentials, HTTPBearer
from fastapi.security.utils import get_authorization_scheme_param
from starlette.requests import HTTPConnection

from api.auth import authorise, bearer
from api.errors import ApiError
from api.services import Services
from api.settings import Settings
from api.subscriptions import EventHub
from kb.protocol import KnowledgeBase
from scene.world import World


def services_of(conn: HTTPConnection) -> Services:
    """The service's parts, as the app's lifespan set them."""
    services: Services = conn.app.state.services
    return services


# Each dependency reads the services straight from the connection rather than through another
# dependency: FastAPI resolves every nested dependency per request (its cache lookup included), a
# measurable part of a request to a route that does little else.
async def get_services(conn: HTTPConnection) -> Services:
    return services_of(conn)


ServicesDep = Annotated[Services, Depends(get_services)]


async def get_kb(conn: HTTPConnection) -> KnowledgeBase:
    return services_of(conn).kb


async def get_world(conn: HTTPConnection) -> World:
    world = services_of(conn).world
    if world is None:  # a reader forwards /scene to the writer before routing
        raise ApiError(503, "scene_elsewhere", "the scene is kept by the writer service")
    return world


async def get_settings(conn: HTTPConnection) -> Settings:
    return services_of(conn).settings


async def get_hub(conn: HTTPConnection) -> EventHub:
    return services_of(conn).hub


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


class Access(HTTPBearer):
    """The access check of a route, as one dependency: the bearer token read (what declares the
    route's security scheme, as ``bearer`` does) and checked in the same call. A check depending on
    ``Credentials`` was two dependencies, each solved anew per request."""

    def __init__(self, *, write: bool) -> None:
        super().__init__(auto_error=False, scheme_name=bearer.scheme_name,
                         description=bearer.model.description)
        self.write = write

    async def __call__(self, request: HTTPConnection) -> HTTPAuthorizationCredentials | None:
        credentials = await super().__call__(request)
        authorise(services_of(request).settings, credentials.credentials if credentials else None,
                  write=self.write)
        return credentials


async def require_read_stream(conn: HTTPConnection, credentials: Credentials,
                        access_token: Annotated[str | None, Query(
                            description="the token, for clients that cannot send headers")] = None,
                        ) -> None:
    presented = credentials.credentials if credentials else access_token
    authorise(services_of(conn).settings, presented, write=False)


ReadAccess = Depends(Access(write=False))
StreamReadAccess = Depends(require_read_stream)
WriteAccess = Depends(Access(write=True))
