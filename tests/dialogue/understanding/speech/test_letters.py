"""Words spelled out letter by letter, joined into the word the KB knows."""

import pytest

from dialogue import intents as I
from dialogue.understanding.speech.letters import joined
from kb import KB
from tests.dialogue.conftest import lexicon_of, scene_kb
from tests.dialogue.understanding.test_interpret import say


@pytest.fixture
def garden() -> KB:
    return scene_kb(
        None,
        "tongs_1 rdf:type Artifact", 'tongs_1 rdfs:label "BBQ tongs"', "myself sees tongs_1",
        "pen_1 rdf:type Artifact", 'pen_1 rdfs:label "3D pen"', "myself sees pen_1",
        "mat_1 rdf:type Artifact", 'mat_1 rdfs:label "mat"', "myself sees mat_1",
    )  # fmt: skip


@pytest.mark.parametrize(
    ("text", "meant"),
    [
        ("pass me the b b q tongs", "pass me the bbq tongs"),
        ("grab the B B Q tongs", "grab the BBQ tongs"),
        ("where is the 3 d pen", "where is the 3d pen"),
        # letters that spell nothing the KB knows stay letters (chat's "u" is read later as "you")
        ("can u get the mat", "can u get the mat"),
        ("put it on row a b", "put it on row a b"),
        ("take table 4 5", "take table 4 5"),  # numbers are no letters of a word
    ],
)
def test_letters_that_spell_a_name_are_joined(garden: KB, text: str, meant: str) -> None:
    assert joined(text, lexicon_of(garden)) == meant


def test_a_name_spelled_out_is_understood_without_a_guess(garden: KB) -> None:
    out = say(garden, "hand me the b b q tongs")
    assert (out.intent, out.roles["object"]) == (I.BRING_OBJECT, "tongs_1")
    assert out.confidence == 0.9 and not out.guessed  # the letters say the word: no slip, no guess
