"""The robot's initiative: a person who becomes engaged is engaged with, and greeted by name."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from dialogue import intents as I
from dialogue.initiative import Initiative, InitiativeConfig
from dialogue.pushed.bus import IntentBus
from kb import KB


class Clock:
    def __init__(self) -> None:
        self.now = 1000.0

    def __call__(self) -> float:
        return self.now


@pytest.fixture
def kb() -> Iterator[KB]:
    kb = KB()
    kb.update(["person_bob rdf:type Human", 'person_bob rdfs:label "Bob"', "person_x rdf:type Human"])
    yield kb
    kb.close()


def said(bus: IntentBus) -> list[tuple[str, str, str, str]]:
    events, _ = bus.since(0)
    return [(e.intent.intent, e.intent.data["recipient"], e.intent.source, e.response) for e in events]


def engage(kb: KB, person: str) -> None:
    kb.update([f"{person} engagementLevel engaged"])


def disengage(kb: KB, person: str) -> None:
    kb.update([f"{person} engagementLevel disengaged"])


def test_a_person_becoming_engaged_is_engaged_with_and_greeted_by_name(kb: KB) -> None:
    bus, clock = IntentBus(), Clock()
    initiative = Initiative(kb, bus, InitiativeConfig(interval=60), clock)
    assert initiative.start()
    try:
        engage(kb, "person_bob")
        engage(kb, "person_x")
        initiative.join()
    finally:
        initiative.stop()
    assert said(bus) == [
        (I.ENGAGE_WITH, "person_bob", I.ROBOT_ITSELF, ""), (I.GREET, "person_bob", I.ROBOT_ITSELF, "Hello Bob!"),
        (I.ENGAGE_WITH, "person_x", I.ROBOT_ITSELF, ""), (I.GREET, "person_x", I.ROBOT_ITSELF, "Hello!"),
    ]
    events, _ = bus.since(0)
    assert [e.intent.modality for e in events] == [I.MODALITY_MOTION, I.MODALITY_INTERNAL] * 2
    assert {e.origin for e in events} == {"initiative"} and {e.dialogue_id for e in events} == {None}


def test_greeted_once_within_the_interval_and_again_after_it(kb: KB) -> None:
    bus, clock = IntentBus(), Clock()
    initiative = Initiative(kb, bus, InitiativeConfig(interval=60), clock)
    initiative.engaged("person_bob")
    clock.now += 30  # left and came back within the interval: engaged with, not greeted again
    initiative.engaged("person_bob")
    clock.now += 31
    kb.update(['person_bob lastSpokeAt "2025-06-01T10:00:00+00:00"^^xsd:dateTime'])
    initiative.engaged("person_bob")
    assert [(intent, response) for intent, _, _, response in said(bus)] == [
        (I.ENGAGE_WITH, ""), (I.GREET, "Hello Bob!"), (I.ENGAGE_WITH, ""),
        (I.ENGAGE_WITH, ""), (I.GREET, "Hello Bob, nice to see you again!")]


def test_only_the_transition_into_engaged_counts(kb: KB) -> None:
    bus = IntentBus()
    initiative = Initiative(kb, bus, InitiativeConfig(greet=False))
    initiative.start()
    try:
        kb.update(["person_bob engagementLevel engaging"])
        engage(kb, "person_bob")
        engage(kb, "person_bob")  # no change: nothing new
        kb.update(["person_bob engagementLevel engaged"], models=["person_x"])  # someone's belief
        disengage(kb, "person_bob")
        engage(kb, "person_bob")
        initiative.join()
    finally:
        initiative.stop()
    assert [(i, r) for i, r, _, _ in said(bus)] == [(I.ENGAGE_WITH, "person_bob")] * 2


def test_a_kb_without_commits_has_no_initiative() -> None:
    class Replica:
        pass

    assert not Initiative(Replica(), IntentBus()).start()  # type: ignore[arg-type]
