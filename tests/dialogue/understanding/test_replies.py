"""How the replies name things: with "the", or as a name of their own."""

from __future__ import annotations

import pytest

from dialogue.understanding.replies import the
from tests.dialogue.conftest import build_snapshot, english, scene_kb


@pytest.mark.parametrize(
    ("label", "said"),
    [("armchair", "the armchair"), ("Walter's armchair", "Walter's armchair"), ("screen 2", "screen 2"),
     ("walter's armchair", "the walter's armchair")],  # (no capital: no name of someone's)
)  # fmt: skip
def test_a_thing_named_as_someones_takes_no_article(label: str, said: str) -> None:
    kb = scene_kb(None, "chair_1 rdf:type Artifact", f'chair_1 rdfs:label "{label}"', "myself sees chair_1")
    snapshot = build_snapshot(kb)
    assert the(english(), snapshot, snapshot.entities["chair_1"]) == said
