"""People's names heard or typed in another spelling, read as the KB's by their sound."""

import pytest

from dialogue import intents as I
from dialogue.understanding.speech.heardnames import heard_name, sound_key
from kb import KB
from tests.dialogue.conftest import lexicon_of, scene_kb
from tests.dialogue.understanding.test_interpret import say


@pytest.fixture
def people() -> KB:
    return scene_kb(
        None,
        "p_g rdf:type Human", 'p_g rdfs:label "Geoff"', "p_s rdf:type Human", 'p_s rdfs:label "Stephen"',
        "p_r rdf:type Human", 'p_r rdfs:label "Rhys"', "p_a rdf:type Human", 'p_a rdfs:label "Ayesha"',
        "p_k rdf:type Human", 'p_k rdfs:label "Mr Kowalski"', "person_bob rdf:type Human",
        'person_bob rdfs:label "Bob"', "room_2 rdf:type ZoneOfInterest", 'room_2 rdfs:label "surgery two"',
    )  # fmt: skip


@pytest.mark.parametrize(
    ("said", "name"),
    [("jeff", "geoff"), ("steven", "stephen"), ("reese", "rhys"), ("aisha", "ayesha"), ("kowalsky", "kowalski")],
)
def test_a_name_is_heard_by_its_sound(people: KB, said: str, name: str) -> None:
    assert sound_key(said) == sound_key(name)
    assert heard_name(said, lexicon_of(people)) == name


def test_a_sound_of_no_name_or_too_short_names_no_one(people: KB) -> None:
    lex = lexicon_of(people)
    assert heard_name("kettle", lex) is None and heard_name("a", lex) is None


def test_a_name_wins_over_a_number_word_and_the_turn_is_a_guess(people: KB) -> None:
    out = say(people, "can you bring steven through to surgery two please")
    assert (out.intent, out.roles) == (I.GUIDE, {"recipient": "p_s", "goal": "room_2"})
    assert out.guessed and out.confidence < 0.9
    out = say(people, "tell jeff his reservation has come in")
    assert (out.intent, out.roles["recipient"]) == (I.SAY, "p_g")
