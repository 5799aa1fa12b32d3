"""Corrections of the request just made, and of a correction just made."""

import pytest

from dialogue import intents as I
from kb import KB
from tests.dialogue.conftest import scene_kb
from tests.dialogue.understanding.test_interpret import say

LEA = "person_lea"


@pytest.fixture
def pantry() -> KB:
    return scene_kb(
        None,
        "myself rdf:type Robot",
        "pantry rdf:type ZoneOfInterest", 'pantry rdfs:label "pantry"',
        "larder rdf:type ZoneOfInterest", 'larder rdfs:label "larder"',
        f"{LEA} rdf:type Human", f'{LEA} rdfs:label "Lea"', f"myself sees {LEA}",
        "person_tam rdf:type Human", 'person_tam rdfs:label "Tam"', "myself sees person_tam",
        "jar_1 rdf:type Container", 'jar_1 rdfs:label "jar"', "jar_1 hasColor green", "myself sees jar_1",
        "jar_2 rdf:type Container", 'jar_2 rdfs:label "jar"', "jar_2 hasColor amber", "myself sees jar_2",
    )  # fmt: skip


def _after(*turns: str) -> list[tuple[str, str]]:
    """A conversation in which every turn of the person's was acknowledged."""
    return [(who, text) for said in turns for who, text in (("user", said), ("robot", "OK."))]


def test_a_correction_after_a_correction_corrects_the_request_as_corrected(pantry: KB) -> None:
    history = _after("bring me the green jar", "no, the amber one")
    out = say(pantry, "no, the other one", speaker=LEA, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "jar_1", "recipient": LEA}), out.reply
    # a correction of another role keeps what the first one corrected
    out = say(pantry, "sorry, I meant to Tam", speaker=LEA, history=history)
    assert out.roles == {"object": "jar_2", "recipient": "person_tam"}, out.reply
    again = _after("bring me the green jar", "no, the amber one", "sorry, I meant to Tam")
    assert say(pantry, "no, the green one", speaker=LEA, history=again).roles == {
        "object": "jar_1", "recipient": "person_tam"}  # fmt: skip


def test_a_correction_needs_a_request_at_the_end_of_its_corrections(pantry: KB) -> None:
    # words that were no correction of anything leave nothing to correct
    history = _after("the amber one")
    assert say(pantry, "no, the other one", speaker=LEA, history=history).intent is None
    # and corrections reach back a few steps only
    far = _after("bring me the green jar", "no, the amber one", "no, the green one", "no, the amber one",
                 "no, the green one")  # fmt: skip
    assert say(pantry, "no, the other one", speaker=LEA, history=far).intent is None


def test_the_same_again_with_another_thing_is_the_request_for_it(pantry: KB) -> None:
    history = _after("take the green jar to the larder")
    out = say(pantry, "now do the same with the amber one", speaker=LEA, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "jar_2", "recipient": "larder"}), out.reply
    out = say(pantry, "same for the pantry", speaker=LEA, history=history)
    assert out.roles == {"object": "jar_1", "recipient": "pantry"}, out.reply
    # with nothing done before it, nothing is done again
    assert say(pantry, "do the same with the amber one", speaker=LEA).intent is None


def test_a_correction_said_before_why_is_the_correction(pantry: KB) -> None:
    history = _after("take the green jar to the larder")
    out = say(pantry, "oh, not the larder, the pantry. I want some fresh air.", speaker=LEA, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "jar_1", "recipient": "pantry"}), out.reply


def test_the_same_again_with_what_could_be_either_role_is_not_guessed(pantry: KB) -> None:
    pantry.add(["tray_1 rdf:type Tray", 'tray_1 rdfs:label "tray"', "myself sees tray_1",
                "jar_3 rdf:type Container", 'jar_3 rdfs:label "jar"', "jar_3 isIn larder"])  # fmt: skip
    history = _after("put the green jar on the tray")
    # the amber jar put on the tray, or the green jar put on the amber jar: not said which
    assert say(pantry, "do the same with the amber jar", speaker=LEA, history=history).intent is None
    # a jar (of two it might be) put on the tray, or the green jar put on the jar in sight
    assert say(pantry, "do the same with the jar", speaker=LEA, history=history).intent is None
    out = say(pantry, "do the same with the amber one", speaker=LEA, history=history)  # a jar: the thing
    assert out.roles == {"object": "jar_2", "recipient": "tray_1"}, out.reply


def test_a_correction_that_reads_as_a_request_or_a_refusal_of_its_own_is_the_correction(pantry: KB) -> None:
    history = _after("take the green jar to the larder")
    # "make that": an activity's verb; "wait, no": a refusal; both open a correction here
    out = say(pantry, "Actually, make that the pantry.", speaker=LEA, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "jar_1", "recipient": "pantry"}), out.reply
    out = say(pantry, "Wait, no, to the pantry.", speaker=LEA, history=history)
    assert out.roles == {"object": "jar_1", "recipient": "pantry"}, out.reply
    # a refusal that names nothing instead stays a refusal; with no request before, nothing is corrected
    assert say(pantry, "wait, no, don't", speaker=LEA, history=history).intent is None
    assert say(pantry, "make that the pantry", speaker=LEA).intent != I.BRING_OBJECT


def test_one_more_thing_said_with_too_is_the_request_again_for_it(pantry: KB) -> None:
    history = _after("bring me the green jar")
    for said in ("Thanks! Now the amber one too.", "and the amber one as well"):
        out = say(pantry, said, speaker=LEA, history=history)
        assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "jar_2", "recipient": LEA}), said
    # thanks alone is only thanks; "too" with nothing asked before asks for nothing
    assert say(pantry, "thanks", speaker=LEA, history=history).intent is None
    assert say(pantry, "the amber one too", speaker=LEA).intent is None


def test_a_correction_said_with_a_place_preposition_replaces_the_place(pantry: KB) -> None:
    # (a jar and a box alike as a shelf and a box: the preposition tells which role)
    pantry.add(["shelf_1 rdf:type Container", 'shelf_1 rdfs:label "shelf"', "myself sees shelf_1",
                "box_1 rdf:type Container", 'box_1 rdfs:label "box"', "myself sees box_1"])  # fmt: skip
    history = _after("put the green jar on the shelf")
    for said in ("I meant on the box", "wait, no, on the box"):
        out = say(pantry, said, speaker=LEA, history=history)
        assert (out.intent, out.roles) == (I.PLACE_OBJECT, {"object": "jar_1", "recipient": "box_1"}), said


@pytest.mark.parametrize("text", ["and also the amber jar", "oh and the amber jar too", "plus the amber jar",
                                  "and the amber jar as well please"])
def test_one_more_for_the_request_just_made_is_that_request_again(pantry: KB, text: str) -> None:
    out = say(pantry, text, speaker=LEA, history=_after("give Tam the green jar"))
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "jar_2", "recipient": "person_tam"}), out.reply


def test_one_more_whose_role_is_not_clear_is_not_understood(pantry: KB) -> None:
    history = _after("put the green jar in the pantry")  # (a jar is put in a zone, never a zone on a jar)
    out = say(pantry, "oh and the amber jar too", speaker=LEA, history=history)
    assert (out.intent, out.roles) == (I.PLACE_OBJECT, {"object": "jar_2", "recipient": "pantry"}), out.reply
    pantry.update(["shelf_1 rdf:type dbr:Shelf_(storage)", 'shelf_1 rdfs:label "shelf"', "myself sees shelf_1"])
    # one more thing put on the shelf, or the green jar put on the amber one: neither is guessed, and
    # never a bringing to the speaker
    out = say(pantry, "oh and the amber jar too", speaker=LEA, history=_after("put the green jar on the shelf"))
    assert out.intent is None and not out.understood, out.reply


def test_and_alone_says_one_more_only_before_a_noun_phrase(pantry: KB) -> None:
    history = _after("give Tam the green jar")
    out = say(pantry, "and the amber jar", speaker=LEA, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "jar_2", "recipient": "person_tam"}), out.reply
    assert say(pantry, "and you?", speaker=LEA, history=history).intent is None


@pytest.fixture
def hall() -> KB:
    return scene_kb(
        None,
        "myself rdf:type Robot",
        "hall rdf:type ZoneOfInterest", 'hall rdfs:label "hall"',
        "study rdf:type ZoneOfInterest", 'study rdfs:label "study"',
        f"{LEA} rdf:type Human", f'{LEA} rdfs:label "Lea"', f"myself sees {LEA}",
        "person_tam rdf:type Human", 'person_tam rdfs:label "Tam"', "myself sees person_tam",
        "person_ivo rdf:type Human", 'person_ivo rdfs:label "Ivo"', "myself sees person_ivo",
        "book_1 rdf:type dbr:Book", 'book_1 rdfs:label "book"', "myself sees book_1",
        "scarf_1 rdf:type Cloth", 'scarf_1 rdfs:label "scarf"', "myself sees scarf_1",
    )  # fmt: skip


@pytest.mark.parametrize("said", ["and then the scarf too", "and the scarf as well", "the scarf too"])
def test_one_more_thing_keeps_the_person_the_request_brought_it_to(hall: KB, said: str) -> None:
    history = [("user", "bring the book to Tam"), ("robot", "OK, I'm bringing the book to Tam.")]
    out = say(hall, said, speaker=LEA, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "scarf_1", "recipient": "person_tam"}), said


@pytest.mark.parametrize("said", ["no wait, take Ivo instead", "take Ivo instead"])
def test_the_request_said_again_with_instead_corrects_whom_it_guides(hall: KB, said: str) -> None:
    history = [("user", "take Tam to the study"), ("robot", "OK, I'm guiding Tam to the study.")]
    out = say(hall, said, speaker=LEA, history=history)
    assert (out.intent, out.roles) == (I.GUIDE, {"recipient": "person_ivo", "goal": "study"}), said
    # with no request before it, "instead" corrects nothing: Ivo is no thing to take
    assert say(hall, said, speaker=LEA).intent != I.GUIDE
