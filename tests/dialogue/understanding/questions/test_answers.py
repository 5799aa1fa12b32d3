"""Answers to questions about the situation: where things are, who is somewhere."""

from kb import KB
from tests.dialogue.conftest import scene_kb
from tests.dialogue.understanding.test_interpret import say


def test_where_is_a_name_several_share_says_where_each_is(office: KB) -> None:
    reply = say(office, "where is the mug?").reply
    assert "green mug" in reply and "yellow mug" in reply


def test_where_is_one_in_sight_and_one_not_names_both() -> None:
    kb = scene_kb(
        None, "myself rdf:type Robot",
        "hall rdf:type ZoneOfInterest", 'hall rdfs:label "hall"',
        "shed rdf:type ZoneOfInterest", 'shed rdfs:label "shed"',
        "cup_r rdf:type dbr:Cup", 'cup_r rdfs:label "cup"', "cup_r hasColor red", "cup_r isIn hall",
        "myself sees cup_r",
        "cup_g rdf:type dbr:Cup", 'cup_g rdfs:label "cup"', "cup_g hasColor green", "cup_g isIn shed",
    )  # fmt: skip
    reply = say(kb, "where's the cup?").reply
    assert "red cup" in reply and "green cup" in reply and "shed" in reply
