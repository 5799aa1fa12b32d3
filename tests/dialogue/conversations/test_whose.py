"""Issue 30, class 7: "my X" that the KB says is someone else's, or nobody's, is said so before
the robot acts."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from tests.dialogue.conversations.talk import Talk, person, robot, talking, thing, zone

OFFICE = [
    *robot(), *zone("office", "office"),
    *person("person_noor", "Noor", zone="office", seen=True), *person("person_abel", "Abel"),
    *thing("stapler_1", "Artifact", "stapler", owner="person_abel", zone="office", seen=True),
    *thing("scarf_1", "Artifact", "scarf", zone="office", seen=True),
    *thing("badge_1", "Artifact", "badge", owner="person_noor", zone="office", seen=True),
]


@pytest.fixture
def talk() -> Iterator[Talk]:
    with talking(OFFICE, "person_noor") as talk:
        yield talk


def test_my_thing_that_is_someone_elses_is_said_whose_first(talk: Talk) -> None:
    said = talk("bring me my stapler")
    assert said.reply == "The stapler is Abel's, not yours. OK, I will bring the stapler to you."
    assert said.intents == (("__intent_bring_object__", {"object": "stapler_1", "recipient": "person_noor"}),)


def test_my_thing_that_is_nobodys_is_said_so_and_ones_own_plainly(talk: Talk) -> None:
    assert talk("pick up my scarf").reply == "As far as I know, the scarf belongs to nobody. OK, I will pick up the scarf."
    assert talk("pick up my badge").reply == "OK, I will pick up the badge."
