"""A thing taken or carried to furniture that holds things is put there; to a room or a person,
brought."""

import pytest

from dialogue import intents as I
from kb import KB
from tests.dialogue.understanding.test_interpret import say


@pytest.mark.parametrize(
    ("text", "place"),
    [("carry the pear over to the desk", "desk_1"), ("could you take the stapler to the shelf?", "shelf_9")],
)
def test_a_thing_carried_to_furniture_that_holds_things_is_put_there(office: KB, text: str, place: str) -> None:
    out = say(office, text)
    thing = "pear_1" if "pear" in text else "stapler_1"
    assert (out.intent, out.roles) == (I.PLACE_OBJECT, {"object": thing, "recipient": place})
    assert out.reply.startswith("OK, I will put the")


@pytest.mark.parametrize(
    ("text", "to"),
    [("take the pear to the bathroom", "bathroom"), ("carry the pear to Carol", "person_carol"),
     ("bring the pear to the desk", "desk_1")],
)  # fmt: skip
def test_a_thing_taken_to_a_room_or_a_person_or_brought_to_furniture_is_brought(office: KB, text: str, to: str) -> None:
    out = say(office, text)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "pear_1", "recipient": to})


def test_a_thing_taken_to_a_table_known_by_its_number_is_served_there(office: KB) -> None:
    office.update(["table_4 rdf:type dbr:Table_(furniture)", 'table_4 rdfs:label "table 4"', "myself sees table_4"])
    out = say(office, "take the pear to table four")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "pear_1", "recipient": "table_4"})
