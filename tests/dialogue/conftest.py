"""Shared helpers: KBs built from the eval scenes kept next to these tests (tests/dialogue/eval/)."""

from __future__ import annotations

import functools
from collections.abc import Iterator
from pathlib import Path

import pytest

from dialogue.reference.grounding import Snapshot, build_snapshot
from dialogue.reference.lexicon import Lexicon
from dialogue.understanding.language import Language
from kb import KB

EVAL_DIR = Path(__file__).parent / "eval"


def scene_statements(name: str) -> list[str]:
    text = (EVAL_DIR / "scenes" / f"{name}.txt").read_text(encoding="utf-8")
    return [s.strip() for s in text.splitlines() if s.strip() and not s.strip().startswith("#")]


def scene_kb(name: str | None = None, *facts: str) -> KB:
    kb = KB()
    if name:
        kb.update(scene_statements(name))
    if facts:
        kb.update(list(facts))
    return kb


@functools.cache
def english() -> Language:
    """English, as every engine reads it (a packaged language is read once per process)."""
    return Language.load("en")


def lexicon_of(kb: KB) -> Lexicon:
    return Lexicon(build_snapshot(kb), english())


@pytest.fixture
def kitchen() -> Iterator[KB]:
    kb = scene_kb("kitchen")
    yield kb
    kb.close()


@pytest.fixture
def cups() -> Iterator[KB]:
    kb = scene_kb("two_cups")
    yield kb
    kb.close()


@pytest.fixture
def office() -> Iterator[KB]:
    kb = scene_kb("office")
    yield kb
    kb.close()


@pytest.fixture
def kitchen_snapshot(kitchen: KB) -> Snapshot:
    return build_snapshot(kitchen)


#: A home the memory and statement tests talk about: what the robot perceives, and people to tell it
#: things.
HOME = [
    "myself rdf:type Robot",
    'kitchen rdf:type ZoneOfInterest', 'kitchen rdfs:label "kitchen"',
    'living_room rdf:type ZoneOfInterest', 'living_room rdfs:label "living room"',
    "table_1 rdf:type dbr:Table_(furniture)", "table_1 isIn kitchen", "myself sees table_1",
    "mug_red rdf:type dbr:Cup", 'mug_red rdfs:label "mug"', "mug_red hasColor red", "mug_red isOn table_1",
    "myself sees mug_red",
    'keys_1 rdf:type Artifact', 'keys_1 rdfs:label "keys"', "keys_1 isIn kitchen",
    'drawer_1 rdf:type Container', 'drawer_1 rdfs:label "drawer"', "drawer_1 isIn kitchen",
    "sofa_1 rdf:type cyc:Sofa-PieceOfFurniture", "sofa_1 isIn living_room", "myself sees sofa_1",
    'glasses_1 rdf:type Artifact', 'glasses_1 rdfs:label "glasses"', "glasses_1 isIn living_room",
    "phone_1 rdf:type dbr:Smartphone", "phone_1 isOn table_1", "myself sees phone_1",
    'book_1 rdf:type dbr:Book', 'book_1 rdfs:label "cookbook"', "book_1 isOn table_1", "myself sees book_1",
    "book_1 belongsTo person_alice",
    "remote_1 rdf:type Remote", "remote_1 isOn sofa_1", "myself sees remote_1",
    "person_alice rdf:type Human", 'person_alice rdfs:label "Alice"', "myself sees person_alice",
    "person_ines rdf:type Human", 'person_ines rdfs:label "Ines"',
    "person_x rdf:type Human", "myself sees person_x",
    "person_bob rdf:type Human",
]


@pytest.fixture
def home() -> Iterator[KB]:
    kb = KB()
    kb.update(HOME)
    yield kb
    kb.close()
