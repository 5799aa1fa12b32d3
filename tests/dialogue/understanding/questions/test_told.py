"""Questions about what people told: facts with no object."""

from __future__ import annotations

import pytest

from dialogue.history import Utterance
from dialogue.understanding.questions.told import Asking
from kb import KB
from tests.dialogue.conftest import lexicon_of

BOB = "person_bob"


def asked(kb: KB, text: str, history: list[Utterance] | None = None) -> list[tuple[str | None, ...]] | None:
    read = Asking(lexicon_of(kb), BOB, history or []).read(text)
    return None if read is None else [(f.subject, f.predicate, f.object) for f in read]


@pytest.mark.parametrize(("text", "expected"), [
    ("what do I like?", (BOB, "likes", None)),
    ("What does Alice like?", ("person_alice", "likes", None)),
    ("what does Alice love", ("person_alice", "likes", None)),
    ("what does Alice hate?", ("person_alice", "dislikes", None)),
    ("what does Alice not like?", ("person_alice", "dislikes", None)),
    ("what don't I like", (BOB, "dislikes", None)),
    ("what's my name?", (BOB, "name", None)),
    ("who am I?", (BOB, "name", None)),
    ("do you remember me?", (BOB, "name", None)),
])
def test_questions_about_what_was_told(home: KB, text: str, expected: tuple[str | None, ...]) -> None:
    assert asked(home, text) == [expected]


def test_a_pronoun_is_the_person_just_spoken_of(home: KB) -> None:
    history = [Utterance(BOB, "Alice is in the kitchen")]
    assert asked(home, "what does she like?", history) == [("person_alice", "likes", None)]
    assert asked(home, "what is her name?", history) == [("person_alice", "name", None)]


def test_someone_elses_name_is_asked_about_by_their_name_or_a_pronoun(home: KB) -> None:
    assert asked(home, "what is Alice's name?") == [("person_alice", "name", None)]
    assert asked(home, "what's the name of Alice?") == [("person_alice", "name", None)]
    assert asked(home, "what is your name?") is None  # the robot's: the situation questions answer it
    assert asked(home, "what is her name?") is None  # nobody spoken of yet


@pytest.mark.parametrize("text", ["what do you see", "what does Zoe like", "whose mug is this", "what is it"])
def test_other_questions_are_not_these(home: KB, text: str) -> None:
    assert asked(home, text) is None


def test_where_a_thing_is_that_the_robot_has_no_place_for_asks_what_was_told(home: KB) -> None:
    home.update(['diary_1 rdf:type Artifact', 'diary_1 rdfs:label "diary"'])
    for text in ("where is the diary?", "do you know where the diary is", "any idea where the diary is?"):
        assert asked(home, text) == [("diary_1", "isIn", None)]
    home.update(["myself sees diary_1"])  # seen: the situation answers it, as it does a placed thing
    assert asked(home, "where is the diary?") is None
