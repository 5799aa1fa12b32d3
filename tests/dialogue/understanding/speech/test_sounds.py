"""Names heard as other words: by their sound, two words for one, a homophone, a key slip."""

import pytest

from dialogue import intents as I
from dialogue.reference.english import tokens
from dialogue.reference.resolution import THING
from dialogue.understanding.interpret import Interpreter
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.speech.sounds import clipped, slipped, slips, sounds_alike
from kb import KB
from tests.dialogue.conftest import lexicon_of, scene_kb


@pytest.fixture
def studio() -> KB:
    return scene_kb(
        None,
        "k_blue rdf:type Artifact", 'k_blue rdfs:label "blue kettle"', "myself sees k_blue",
        "k_red rdf:type Artifact", 'k_red rdfs:label "red kettle"', "myself sees k_red",
        "mat_1 rdf:type Artifact", 'mat_1 rdfs:label "bath mat"', "myself sees mat_1",
        "pencil_1 rdf:type Artifact", 'pencil_1 rdfs:label "pencil"', "myself sees pencil_1",
        "pen_1 rdf:type Artifact", 'pen_1 rdfs:label "pen"', "myself sees pen_1",
        "kitchen_1 rdf:type ZoneOfInterest", 'kitchen_1 rdfs:label "kitchen"',
        "cap_1 rdf:type Artifact", 'cap_1 rdfs:label "cap"', "myself sees cap_1",
    )  # fmt: skip


def say(kb: KB, text: str) -> Outcome:
    return Interpreter(lexicon_of(kb), "user1").interpret(text)


def test_words_that_sound_alike_share_their_consonants() -> None:
    assert sounds_alike("blew", "blue") and sounds_alike("matt", "mat") and sounds_alike("pensill", "pencil")
    assert not sounds_alike("blue", "glue") and not sounds_alike("to", "too")  # one sound says too little


def test_slips_of_a_word_are_words_of_the_kbs_names(studio: KB) -> None:
    lex = lexicon_of(studio)
    assert "blue" in slips("blew", lex)
    assert "mat" in slips("matt", lex)
    assert slips("zebra", lex) == []


@pytest.mark.parametrize(
    ("text", "obj"),
    [
        ("pick up the blew kettle", "k_blue"),  # sounds alike, in a name of several words
        ("grab the bath matt", "mat_1"),
        ("hand me the pen sill", "pencil_1"),  # two words heard for one
    ],
)
def test_a_misheard_name_is_read_as_a_guess(studio: KB, text: str, obj: str) -> None:
    out = say(studio, text)
    assert out.roles.get("object") == obj and out.guessed, out.reply
    assert out.confidence < 0.9


def test_one_word_heard_for_one_other_is_too_weak_a_clue(studio: KB) -> None:
    # "cup" sounds like "cap", but a single word for a single word could be anything not in sight.
    out = say(studio, "pick up the cup")
    assert out.intent is None and not out.guessed


def test_two_words_read_as_one_must_name_one_thing(studio: KB) -> None:
    lex = lexicon_of(studio)
    assert slipped(lex, tuple(tokens("the pen sill")), THING, None) is not None
    assert slipped(lex, tuple(tokens("the big sill")), THING, None) is None


def test_a_place_misheard_in_two_words(studio: KB) -> None:
    out = say(studio, "go to the kit chin")
    assert (out.intent, out.roles, out.guessed) == (I.MOVE_TO, {"goal": "kitchen_1"}, True), out.reply


def test_a_word_said_short_is_the_one_longer_name_it_starts() -> None:
    kb = scene_kb(
        None,
        "mic_1 rdf:type Artifact", 'mic_1 rdfs:label "microphone"', "myself sees mic_1",
        "amp_1 rdf:type Artifact", 'amp_1 rdfs:label "amplifier"', "myself sees amp_1",
        "board_1 rdf:type Artifact", 'board_1 rdfs:label "cupboard"', "myself sees board_1",
        "cab_1 rdf:type Artifact", 'cab_1 rdfs:label "cabinet"', "myself sees cab_1",
        "cab_2 rdf:type Artifact", 'cab_2 rdfs:label "cabbage"', "myself sees cab_2",
    )  # fmt: skip
    lex = lexicon_of(kb)
    found = clipped(lex, tokens("the mic"), THING, None)
    assert found is not None and found.id == "mic_1"
    found = clipped(lex, tokens("the amp"), THING, None)
    assert found is not None and found.id == "amp_1"
    assert clipped(lex, tokens("the cup"), THING, None) is None  # "cupboard" goes on with a word: "board"
    assert clipped(lex, tokens("the cab"), THING, None) is None  # the cabinet or the cabbage: not one
    kb.close()
