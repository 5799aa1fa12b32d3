"""Open-world reference: the head noun names the thing; only a contradicted known fact eliminates."""

import pytest

from dialogue import intents as I
from dialogue.reference.headnoun import resolve_head
from dialogue.reference.resolution import THING, resolve
from kb import KB
from tests.dialogue.conftest import lexicon_of, scene_kb
from tests.dialogue.understanding.test_interpret import say


@pytest.mark.parametrize(
    ("text", "obj"),
    [
        ("grab the old stapler", "stapler_1"),  # a word the KB does not know
        ("take the laptop from the kitchen counter", "laptop_1"),  # a place the KB does not know
        ("pick up the notebook that is on the shelf", "notebook_1"),  # a relative clause that holds
        ("take the stapler next to the pear", "stapler_1"),  # a relation with no fact either way
        ("grab the bottle of umbrella", None),  # the head is "bottle": nothing is one
        ("take the notebook lying on the shelf", "notebook_1"),  # how it is placed: no evidence, no head
        ("grab the stapler sitting on the desk", "stapler_1"),
    ],
)
def test_unverifiable_modifiers_do_not_eliminate_a_unique_candidate(office: KB, text: str, obj: str | None) -> None:
    out = say(office, text)
    if obj is None:
        assert out.intent is None and not out.clarify
    else:
        assert (out.intent, out.roles) == (I.GRAB_OBJECT, {"object": obj}), out.reply


@pytest.mark.parametrize(
    "text",
    [
        "grab the blue laptop",  # the laptop is known to be gray
        "take the stapler on the shelf",  # the stapler is known to be on the desk
        "take the umbrella in the office",  # the umbrella is known to be in the hallway
    ],
)
def test_a_modifier_contradicting_a_known_fact_eliminates(office: KB, text: str) -> None:
    out = say(office, text)
    assert out.intent is None and not out.clarify and "don't" in out.reply


def test_an_unverifiable_modifier_cannot_choose_between_candidates(office: KB) -> None:
    out = say(office, "grab the heavy mug")
    assert out.clarify and out.intent is None and "green" in out.reply and "yellow" in out.reply


def test_a_known_owner_contradicts_and_confirms() -> None:
    from tests.dialogue.conftest import scene_kb

    kb = scene_kb("office", "mug_green belongsTo person_bob", "mug_yellow belongsTo person_carol")
    try:
        lex = lexicon_of(kb)
        assert [e.id for e in resolve_head(lex, ["carol", "heavy", "mug"], THING)] == ["mug_yellow"]
        assert resolve_head(lex, ["dan", "heavy", "mug"], THING) == []
    finally:
        kb.close()


def test_a_part_of_a_thing_names_the_thing(office: KB) -> None:
    out = say(office, "go to the far end of the hallway")
    assert (out.intent, out.roles) == (I.MOVE_TO, {"goal": "hallway"})
    out = say(office, "put the pear at the head of the desk")
    assert (out.intent, out.roles) == (I.PLACE_OBJECT, {"object": "pear_1", "recipient": "desk_1"})


def test_several_things_are_never_one_by_their_head(office: KB) -> None:
    lex = lexicon_of(office)
    assert resolve(lex, ["both", "heavy", "mugs"], THING).matches == ()
    assert resolve_head(lex, ["the", "stapler", "and", "the", "laptop"], THING) == []


@pytest.mark.parametrize(
    "text", ["walk Carol back home to the hallway right now ok", "take the stapler whatsit the floppy", "where is carol's floppy"]
)
def test_a_phrase_mixing_known_names_and_unknown_words_is_not_understood(office: KB, text: str) -> None:
    out = say(office, text)
    assert out.intent is None and not out.understood, out.reply


def test_a_phrase_of_words_the_kb_does_not_name_is_not_understood(office: KB) -> None:
    # (English, but "unicorn" may be how the speaker calls a thing the KB names otherwise)
    out = say(office, "grab the unicorn")
    assert out.intent is None and not out.understood, out.reply


def test_either_of_two_alternatives(office: KB) -> None:
    out = say(office, "bring me a unicorn or a pear")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "pear_1", "recipient": "person_bob"})


def test_a_kind_word_names_the_general_thing_and_colour_still_filters(office: KB) -> None:
    out = say(office, "bring me the yellow teacup")  # "teacup" < "cup" (lang/en/lexicon.txt)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "mug_yellow", "recipient": "person_bob"})


def test_walking_a_person_somewhere_is_guiding(office: KB) -> None:
    out = say(office, "could you walk Carol back to the hallway")
    assert (out.intent, out.roles) == (I.GUIDE, {"recipient": "person_carol", "goal": "hallway"})


def _lamps(*facts: str) -> KB:
    return scene_kb(
        None,
        "hall rdf:type ZoneOfInterest", 'hall rdfs:label "hall"',
        "den rdf:type ZoneOfInterest", 'den rdfs:label "den"',
        "door_1 rdf:type Artifact", 'door_1 rdfs:label "door"', "door_1 isIn hall", "myself sees door_1",
        "sofa_1 rdf:type Artifact", 'sofa_1 rdfs:label "sofa"', "sofa_1 isIn den", "myself sees sofa_1",
        "lamp_1 rdf:type Artifact", 'lamp_1 rdfs:label "lamp"', "myself sees lamp_1",
        "lamp_2 rdf:type Artifact", 'lamp_2 rdfs:label "lamp"', "myself sees lamp_2",
        *facts,
    )  # fmt: skip


@pytest.mark.parametrize("near", ["by", "next to", "near", "beside", "close to"])
def test_a_thing_said_to_be_near_another_is_the_one_the_kb_puts_there(near: str) -> None:
    kb = _lamps("lamp_1 isNextTo door_1", "lamp_2 isNextTo sofa_1", "lamp_1 isIn hall", "lamp_2 isIn hall")
    assert [e.id for e in resolve(lexicon_of(kb), f"the lamp {near} the sofa".split(), THING).matches] == [
        "lamp_2"]  # fmt: skip
    out = say(kb, f"go to the lamp {near} the door")
    assert (out.intent, out.roles) == (I.MOVE_TO, {"goal": "lamp_1"}), out.reply


def test_sharing_a_zone_is_weaker_evidence_of_being_near_than_a_fact() -> None:
    # lamp_1 is in the den with the sofa, lamp_2 in the hall: "by the sofa" is the den's lamp
    kb = _lamps("lamp_1 isIn den", "lamp_2 isIn hall")
    assert say(kb, "pick up the lamp by the sofa").roles == {"object": "lamp_1"}
    # both in the den, one known to be next to the sofa: that one
    kb = _lamps("lamp_1 isIn den", "lamp_2 isIn den", "lamp_2 isNextTo sofa_1")
    assert say(kb, "pick up the lamp by the sofa").roles == {"object": "lamp_2"}


def test_nothing_known_of_what_is_near_what_leaves_the_question_open() -> None:
    # no fact either way: "by the door" neither picks a lamp nor rules one out (the open world)
    out = say(_lamps(), "pick up the lamp by the door")
    assert out.intent is None and out.clarify
    assert say(_lamps("lamp_2 isNextTo sofa_1"), "pick up the lamp by the door").clarify


def test_a_word_none_of_the_candidates_has_does_not_pick_the_one_the_robot_sees() -> None:
    # "the staff room" is neither the waiting room the robot sees nor the x-ray room it does not:
    # no guess (with every candidate seen, it asks which: "the heavy mug")
    kb = scene_kb(
        None,
        "room_w rdf:type ZoneOfInterest", 'room_w rdfs:label "waiting room"', "myself sees room_w",
        "room_x rdf:type ZoneOfInterest", 'room_x rdfs:label "x-ray room"',
    )  # fmt: skip
    assert resolve_head(lexicon_of(kb), ("the", "staff", "room"), frozenset({"zone"})) == []
    out = say(kb, "go to the staff room")
    assert out.intent is None and not out.understood
    assert say(kb, "go to the x ray room").roles == {"goal": "room_x"}
    kb.close()


def _containers() -> KB:
    return scene_kb(
        None,
        "tin_1 rdf:type Box", 'tin_1 rdfs:label "coin tin"', "myself sees tin_1",
        "bottle_1 rdf:type dbr:Bottle", 'bottle_1 rdfs:label "red plastic bottle"', "myself sees bottle_1",
    )  # fmt: skip


@pytest.mark.parametrize("text", ["a box of tissues", "a box of tumble dryer sheets"])
def test_a_container_whose_label_names_other_contents_is_not_a_container_of_this(text: str) -> None:
    kb = _containers()
    try:
        assert resolve_head(lexicon_of(kb), text.split(), THING) == []
        out = say(kb, f"get me {text}")
        assert out.intent is None, out.reply
    finally:
        kb.close()


def test_a_container_of_what_its_label_says_or_of_what_nothing_contradicts_is_named() -> None:
    kb = _containers()
    try:
        lex = lexicon_of(kb)
        assert [e.id for e in resolve_head(lex, ["the", "box", "of", "coins"], THING)] == ["tin_1"]
        # Colour, material: what the bottle is like, not what it holds (the open world: it may hold water).
        assert [e.id for e in resolve_head(lex, ["the", "bottle", "of", "water"], THING)] == ["bottle_1"]
    finally:
        kb.close()
