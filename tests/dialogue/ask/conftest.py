"""A form over the two-cups scene: Nina speaks, Oliver is there, a red and a blue cup, two phones."""

from __future__ import annotations

import json

import pytest

from dialogue.ask.form import AskForm, parse_configuration
from dialogue.reference.grounding import build_snapshot
from dialogue.reference.lexicon import Lexicon
from kb import KB
from tests.dialogue.conftest import english

NINA = "person_nina"
PROPERTIES = {
    "age": {"type": "integer", "minimum": 0, "maximum": 130},
    "name": {"type": "string"},
    "colour": {"enum": ["red", "green", "light blue", "blue"]},
    "cup": {"type": "string", "x-kb-class": "dbr:Cup"},
    "tea": {"type": "boolean"},
    "friend": {"type": "string", "format": "kb-person"},
}


def form_of(**properties: object) -> AskForm:
    return parse_configuration(json.dumps({"question": "A few questions?",
                                           "result_schema_properties": properties or PROPERTIES}))


@pytest.fixture
def form() -> AskForm:
    return form_of()


@pytest.fixture
def lexicon(cups: KB) -> Lexicon:
    return Lexicon(build_snapshot(cups), english())
