"""Who is speaking, from the name given when the robot asks (dialogue.sessions.introductions)."""

from __future__ import annotations

import pytest

from dialogue.sessions.introductions import again, opening, speaker_named, told_name
from kb import KB
from tests.dialogue.conftest import english


@pytest.mark.parametrize(("answer", "name"), [
    ("Bob", "Bob"), ("bob", "Bob"), ("I'm Bob", "Bob"), ("it's Bob.", "Bob"), ("my name is mary jane", "Mary Jane"),
    ("Hi, I am Ana", "Ana"), ("hello there, call me Jo", "Jo"), ("well, I'm McKenzie", "McKenzie"),
    ("my name is frank", "Frank"),  # "my name is" says a name surely, an adjective too
])
def test_a_name_is_read_from_the_answer(answer: str, name: str) -> None:
    assert told_name(english(), answer) == name


@pytest.mark.parametrize("answer", ["what do you see?", "I'm tired", "bring me the cup", "my name is not important",
                                    "hello", "I'm thirty", ""])
def test_an_answer_that_gives_no_name_gives_none(answer: str) -> None:
    assert told_name(english(), answer) == ""


def test_the_speaker_is_the_person_of_that_name_else_a_new_id_that_names_nothing_else() -> None:
    with KB() as kb:
        kb += ["person_7 rdf:type Human", 'person_7 rdfs:label "Alice"', "person_bob rdf:type dbr:Cup",
               "person_cy rdf:type Human", "person_dee rdf:type Human", 'person_dee rdfs:label "Deirdre"']
        assert speaker_named(kb, "alice") == "person_7"  # known by name, whatever the case
        assert speaker_named(kb, "Bob") == "person_bob_2"  # person_bob is a cup
        assert speaker_named(kb, "Cy") == "person_cy"  # a person the KB knows without a name
        assert speaker_named(kb, "Dee") == "person_dee_2"  # person_dee is someone else
        assert speaker_named(kb, "Mary Jane") == "person_mary_jane"
        assert speaker_named(kb, "Zoë") == "person_zoe"
        assert sorted(r["h"] for r in kb["?h rdf:type Human"]) == ["person_7", "person_cy", "person_dee"]  # no write


def test_the_questions_ask_the_name_in_words_the_rules_take_an_answer_to() -> None:
    lang = english()
    for question in (opening(lang), again(lang)):
        assert question.endswith("?") and any(words in question.lower() for words in lang.statements.name_asked)
