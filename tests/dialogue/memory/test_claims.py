"""A model's `facts` grounded like intent roles: ids of the situation, names resolved, nothing invented."""

from __future__ import annotations

import re

import pytest

from dialogue.memory.claims import Claim, ground_facts
from dialogue.schema import AnswerError, FactClaim
from kb import KB
from tests.dialogue.memory.conftest import lexicon_of

BOB = "person_bob"


def ground(kb: KB, *facts: tuple[str | None, str | None, str | None]) -> tuple[Claim, ...]:
    found = ground_facts([FactClaim(subject=s, predicate=p, object=o) for s, p, o in facts], lexicon_of(kb), BOB)
    assert found.question is None
    return found.claims


def test_ids_names_and_the_speaker(home: KB) -> None:
    assert ground(home, ("me", "name", "bob"), ("mug_red", "belongsTo", BOB), ("the keys", "isIn", "drawer")) == (
        Claim(BOB, "name", "Bob", "text"), Claim("mug_red", "belongsTo", BOB), Claim("keys_1", "isIn", "drawer_1"))


def test_a_likings_words_are_a_kind_unless_they_are_an_id(home: KB) -> None:
    assert ground(home, (BOB, "likes", "tea"), (BOB, "likes", "book_1"), (BOB, "dislikes", "cookbook")) == (
        Claim(BOB, "likes", "tea", "kind"), Claim(BOB, "likes", "book_1"),
        Claim(BOB, "dislikes", "cookbook", "kind", fallback="book_1"))


def test_a_fact_with_no_object_is_a_question(home: KB) -> None:
    assert ground(home, ("person_alice", "likes", None)) == (Claim("person_alice", "likes", None),)


@pytest.mark.parametrize(("fact", "message"), [
    (("mug_red", "owns", BOB), "facts[0].predicate 'owns' is not one of"),
    (("umbrella_1", "belongsTo", BOB), "facts[0].subject 'umbrella_1' is not the id of a thing"),
    (("mug_red", "belongsTo", "kitchen"), "facts[0].object 'kitchen' is not the id of a person"),
    ((BOB, "name", "!!!"), "facts[0].object '!!!' is not a name"),
    (("kitchen", "likes", "tea"), "facts[0].subject 'kitchen' is not the id of a person"),
    (("keys_1", "isIn", "keys_1"), "facts[0] says 'keys_1' isIn itself"),
    ((BOB, "likes", "me"), "facts[0] says 'person_bob' likes itself"),
])
def test_what_cannot_be_grounded_is_an_answer_error_for_the_repair(
        home: KB, fact: tuple[str, str, str], message: str) -> None:
    with pytest.raises(AnswerError, match=re.escape(message)):
        ground(home, fact)


def test_an_ambiguous_referent_is_asked_about(home: KB) -> None:
    home.update(["mug_blue rdf:type dbr:Cup", 'mug_blue rdfs:label "mug"', "mug_blue hasColor blue",
                 "myself sees mug_blue"])
    found = ground_facts([FactClaim(subject="the mug", predicate="belongsTo", object="me")], lexicon_of(home), BOB)
    assert found.claims == () and found.question is not None and "blue" in found.question


def test_the_robots_id_is_the_robot_not_the_speaker(home: KB) -> None:
    # "myself" is the robot's id in ROS4HRI: "I like you" is a liking of the robot, not of oneself.
    assert ground(home, ("me", "likes", "myself")) == (Claim(BOB, "likes", "myself"),)
    with pytest.raises(AnswerError, match="subject 'myself'"):
        ground(home, ("myself", "likes", "tea"))


def test_the_robot_is_no_speaker_to_learn_from(home: KB) -> None:
    found = ground_facts([FactClaim(subject="me", predicate="name", object="Bob")], lexicon_of(home), "myself")
    assert found.claims == () and found.refusal == "Sorry, I don't know who you are."


def test_me_is_the_speaker_wherever_it_is_said(home: KB) -> None:
    assert ground(home, ("person_alice", "likes", "me")) == (Claim("person_alice", "likes", BOB),)


def test_a_name_is_no_id(home: KB) -> None:
    with pytest.raises(AnswerError, match="the name itself"):
        ground(home, ("me", "name", "person_alice"))
