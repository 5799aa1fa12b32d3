"""The live-server fixtures of tests/api, for the reliability tests; ``slow`` tests run only when
asked for (``-m slow``, or ``SITUATED_SLOW=1``)."""

from __future__ import annotations

import os

import pytest

from tests.api.conftest import live, live_factory

__all__ = ["live", "live_factory"]


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    if "slow" in (config.option.markexpr or "") or os.environ.get("SITUATED_SLOW") == "1":
        return
    skip = pytest.mark.skip(reason="slow: run with -m slow or SITUATED_SLOW=1")
    for item in items:
        if "slow" in item.keywords:
            item.add_marker(skip)
