"""A thing to stay where it is ("great, leave it there", "leave it where it is"): no placing."""

import pytest

from dialogue import intents as I
from kb import KB
from tests.dialogue.conftest import scene_kb
from tests.dialogue.understanding.test_interpret import say

NIA = "person_nia"


@pytest.fixture
def den() -> KB:
    return scene_kb(
        None,
        "myself rdf:type Robot",
        "den rdf:type ZoneOfInterest", 'den rdfs:label "den"',
        f"{NIA} rdf:type Human", f'{NIA} rdfs:label "Nia"', f"myself sees {NIA}",
        "couch_1 rdf:type dbr:Couch", 'couch_1 rdfs:label "couch"', "couch_1 isIn den",
        "shelf_1 rdf:type dbr:Shelf_(storage)", 'shelf_1 rdfs:label "shelf"', "shelf_1 isIn den",
        "remote_1 rdf:type Remote", 'remote_1 rdfs:label "remote"', "remote_1 isOn couch_1",
        "myself sees remote_1",
    )  # fmt: skip


@pytest.mark.parametrize(
    "history",
    [[("user", "is the remote on the couch?"), ("robot", "Yes, the remote is on the couch.")],
     [("user", "put the remote on the couch"), ("robot", "OK, I've put the remote on the couch.")]],
)  # fmt: skip
@pytest.mark.parametrize("said", ["great, leave it there", "perfect, just leave it there"])
def test_leave_it_there_of_the_place_just_spoken_of_places_nothing(
    den: KB, history: list[tuple[str, str]], said: str
) -> None:
    out = say(den, said, speaker=NIA, history=history)
    assert (out.intent, out.understood) == (None, True), out.reply


@pytest.mark.parametrize("said", ["leave it where it is", "leave the remote where it is"])
def test_leave_it_where_it_is_places_nothing(den: KB, said: str) -> None:
    history = [("user", "can you see the remote?"), ("robot", "Yes, it's on the couch.")]
    out = say(den, said, speaker=NIA, history=history)
    assert (out.intent, out.understood, out.clarify) == (None, True, False), out.reply


def test_leaving_a_thing_at_a_place_named_is_a_placing(den: KB) -> None:
    out = say(den, "leave the remote on the shelf", speaker=NIA)
    assert (out.intent, out.roles) == (I.PLACE_OBJECT, {"object": "remote_1", "recipient": "shelf_1"})


def test_a_named_thing_left_there_is_put_there(den: KB) -> None:
    # ("the shelf is free, leave the remote there": the remote is not on the shelf yet)
    history = [("user", "is the shelf free?"), ("robot", "Yes, nothing is on the shelf.")]
    out = say(den, "leave the remote there", speaker=NIA, history=history)
    assert (out.intent, out.roles) == (I.PLACE_OBJECT, {"object": "remote_1", "recipient": "shelf_1"})
