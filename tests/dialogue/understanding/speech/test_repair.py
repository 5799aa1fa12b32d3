"""Self-repairs: what a correction said later replaces, and a request taken back whole."""

import pytest

from dialogue.understanding.speech import repair
from dialogue.understanding.speech.repair import Cleaned, restarted
from kb import KB
from tests.dialogue.conftest import english
from tests.dialogue.understanding.test_interpret import say


def cleaned(text: str) -> Cleaned:
    return repair.cleaned(english(), text)


@pytest.mark.parametrize(
    ("text", "meant"),
    [
        # the phrase said again replaces the one of the same head, wherever it was
        ("put the grey case on the rack sorry i mean the blue case", "put the blue case on the rack"),
        ("take the old box to the hall no the new box", "take the new box to the hall"),
        # the only phrase, of whatever head
        ("fetch the tea sorry i mean the coffee", "fetch the coffee"),
        # of another head, the last phrase, as before
        ("put the pen on the desk sorry i mean the shelf", "put the pen on the shelf"),
        # the whom said after it stays
        ("give the banana to diego no the pear", "give the pear to diego"),
        # a phrase and then the request said again whole: that request
        ("could you give this banana to no the pear give the pear to diego", "give the pear to diego"),
    ],
)
def test_a_phrase_said_again_replaces_the_one_of_its_head(text: str, meant: str) -> None:
    assert cleaned(text).text == meant


@pytest.mark.parametrize(
    "text",
    [
        "tell carol lunch is ready no wait it is not never mind",
        "bring me the pear actually never mind",
        "go to the desk oh wait forget it",
    ],
)
def test_a_request_taken_back_after_a_repair_is_not_done(office: KB, text: str) -> None:
    out = say(office, text)
    assert out.intent is None and out.more == () and not out.reply.startswith("OK, I will")


def test_a_cancel_without_a_repair_is_what_a_message_says(office: KB) -> None:
    out = say(office, "tell Carol never mind")
    assert out.intent == "__intent_say__" and out.roles["object"] == "never mind"


def test_the_right_thing_is_placed_after_the_repair(office: KB) -> None:
    out = say(office, "put the green mug on the shelf, sorry I mean the yellow mug")
    assert (out.intent, out.roles) == ("__intent_place_object__", {"object": "mug_yellow", "recipient": "shelf_9"})


@pytest.mark.parametrize(
    ("text", "said"),
    [("take the box of para- paracetamol to Bea", "take the box of paracetamol to Bea"),
     ("the pen– pencil", "the pencil"),
     # a hyphen inside a word, or a word cut off that the next does not complete, stays
     ("a well-known pen", "a well-known pen"), ("the tea- the mug", "the tea- the mug")],
)  # fmt: skip
def test_a_word_cut_off_and_said_again_in_full_is_said_once(text: str, said: str) -> None:
    assert restarted(text) == said


@pytest.mark.parametrize(
    ("text", "meant"),
    [
        # "nah" alone marks a repair as "no" does: the request after it with another verb replaces it
        ("Put the juice in the - nah, give the juice to Doreen.", "give the juice to doreen"),
        ("put the juice on the nah on the table", "put the juice on the table"),
    ],
)
def test_nah_marks_a_self_repair_as_no_does(text: str, meant: str) -> None:
    assert cleaned(text).text.rstrip(" .") == meant
