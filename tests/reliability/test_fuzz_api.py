"""schemathesis against the service's own OpenAPI document: every operation, with generated valid
and invalid input, against a live server (token configured, reads closed too so that every route's
auth is exercised). No 5xx; responses conform to the documented schemas and content types; auth
is not ignored.

Excluded: the Server-Sent Events streams (``GET /kb/events``...), which never end by themselves and
have their own tests. The WebSocket route and the viewer are not in the OpenAPI document.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import hypothesis
import pytest
import schemathesis
from pydantic import SecretStr
from schemathesis.checks import not_a_server_error
from schemathesis.specs.openapi.checks import (
    content_type_conformance,
    ignored_auth,
    response_schema_conformance,
)

from api.app import create_app
from api.settings import Limits, Settings
from tests.api.conftest import SCENE, Live, serve

TOKEN = "fuzz-token"
AUTH = {"Authorization": f"Bearer {TOKEN}"}
EXAMPLES = 20  # per operation: bounded so the suite stays fast; the slow variant runs more


def _settings() -> Settings:
    # Small limits: generated bodies reach them, so the 413 paths are exercised too.
    return Settings(scene=str(SCENE), token=SecretStr(TOKEN), allow_anonymous_reads=False,
                    limits=Limits(max_body_bytes=64 * 1024, max_statements=50, max_patterns=8))


def _streams(document: dict[str, Any]) -> list[str]:
    """Paths of Server-Sent Events streams: they never end by themselves, so they are left to
    their own tests (tests/api/test_events.py)."""
    return [path for path, item in document["paths"].items()
            if "text/event-stream" in item.get("get", {}).get("responses", {}).get("200", {}).get("content", {})]


# The document is the app's own; building the app does no work (the lifespan is not run here).
DOCUMENT = create_app(_settings()).openapi()
schema = schemathesis.openapi.from_dict(DOCUMENT).exclude(path=_streams(DOCUMENT))


@pytest.fixture(scope="module")
def live() -> Iterator[Live]:
    with serve(create_app(_settings())) as server:
        yield server


# Not negative_data_rejection: pydantic's lax mode accepts coercible values on purpose (0 for
# false, "2" for 2), and the Authorization header sent with every case undoes its header mutations.
CHECKS = [not_a_server_error, response_schema_conformance, content_type_conformance, ignored_auth]


@schema.parametrize()
@hypothesis.settings(max_examples=EXAMPLES, deadline=None, derandomize=True,
                     suppress_health_check=list(hypothesis.HealthCheck))
def test_no_server_error_and_conforming_responses(case: schemathesis.Case[Any], live: Live) -> None:
    case.call_and_validate(base_url=live.url, headers=AUTH, checks=CHECKS)
