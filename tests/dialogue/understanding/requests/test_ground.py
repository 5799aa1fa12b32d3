"""Grounding a request's phrases: what is fetched must be movable, a thing called exactly what is
said is that thing, a kind several things share is asked about, a role nobody named yet is asked."""

import pytest

from dialogue import intents as I
from kb import KB
from tests.dialogue.conftest import scene_kb
from tests.dialogue.understanding.test_interpret import say

LEON = "person_leon"


@pytest.fixture
def flat() -> KB:
    kb = scene_kb(
        None,
        "myself rdf:type Robot",
        "lounge rdf:type ZoneOfInterest", 'lounge rdfs:label "lounge"',
        "bathroom rdf:type ZoneOfInterest", 'bathroom rdfs:label "bathroom"',
        "person_leon rdf:type Human", 'person_leon rdfs:label "Leon"', "person_leon isIn lounge",
        "person_dana rdf:type Human", 'person_dana rdfs:label "Dana"', "person_dana isIn lounge",
        "sofa_1 rdf:type dbr:Couch", "sofa_1 isIn lounge", "myself sees sofa_1",
        "sofa_2 rdf:type dbr:Couch", 'sofa_2 rdfs:label "TV couch"', "sofa_2 isIn lounge",
        "lamp_1 rdf:type Artifact", 'lamp_1 rdfs:label "floor lamp"', "lamp_1 isMovable false",
        "lamp_1 isIn lounge",
        "desk_1 rdf:type dbr:Table_(furniture)", 'desk_1 rdfs:label "desk"', "desk_1 isIn lounge",
        "desk_2 rdf:type dbr:Table_(furniture)", 'desk_2 rdfs:label "standing desk"', "desk_2 isIn lounge",
        "towel_w rdf:type Cloth", 'towel_w rdfs:label "towel"', "towel_w hasColor white",
        "towel_w isIn lounge", "myself sees towel_w",
        "towel_b rdf:type Cloth", 'towel_b rdfs:label "towel"', "towel_b hasColor blue", "towel_b isIn bathroom",
        "mic_1 rdf:type Artifact", 'mic_1 rdfs:label "microphone"', "mic_1 isOn desk_1", "myself sees mic_1",
        "picks_1 rdf:type Artifact", 'picks_1 rdfs:label "guitar picks"', "picks_1 isOn desk_1",
        "stool_1 rdf:type cyc:FurniturePiece", 'stool_1 rdfs:label "stool"', "stool_1 isMovable true",
        "stool_1 isIn lounge",
    )  # fmt: skip
    yield kb
    kb.close()


@pytest.mark.parametrize(
    "text",
    ["Grab the TV couch then!", "move the floor lamp to the bathroom", "lift the desk",
     "carry the floor lamp to me"],
)  # fmt: skip
def test_what_cannot_be_moved_is_answered_with_why_not(flat: KB, text: str) -> None:
    out = say(flat, text, LEON)
    assert out.intent is None and out.understood and not out.clarify
    assert "can't move" in out.reply


def test_furniture_the_kb_says_is_movable_is_carried(flat: KB) -> None:
    out = say(flat, "bring me the stool", LEON)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "stool_1", "recipient": LEON})


def test_a_thing_called_exactly_so_is_that_thing(flat: KB) -> None:
    assert say(flat, "go to the desk", LEON).roles == {"goal": "desk_1"}
    assert say(flat, "put the blue towel on the desk", LEON).roles == {
        "object": "towel_b", "recipient": "desk_1"}  # fmt: skip


def test_a_thing_to_fetch_that_several_share_is_asked_about_in_sight_or_not(flat: KB) -> None:
    out = say(flat, "Get me the towel, would you?", LEON)
    assert out.intent is None and out.clarify and "white" in out.reply and "blue" in out.reply
    answered = say(flat, "The blue one.", LEON, [("user", "Get me the towel, would you?"), ("robot", out.reply)])
    assert (answered.intent, answered.roles) == (I.BRING_OBJECT, {"object": "towel_b", "recipient": LEON})


def test_a_describing_clause_picks_the_thing(flat: KB) -> None:
    out = say(flat, "Pick up the towel that's in the bathroom.", LEON)
    assert (out.intent, out.roles) == (I.GRAB_OBJECT, {"object": "towel_b"})


@pytest.mark.parametrize(
    ("text", "asked", "answer", "roles"),
    [
        ("Could you guide somebody to the bathroom for me?", "Who", "Dana.",
         {"recipient": "person_dana", "goal": "bathroom"}),
        ("Can you guide Dana somewhere?", "Where", "To the bathroom, please.",
         {"recipient": "person_dana", "goal": "bathroom"}),
        ("Put the microphone somewhere safe.", "Where", "On the desk's fine.",
         {"object": "mic_1", "recipient": "desk_1"}),
    ],
)  # fmt: skip
def test_a_role_nobody_named_yet_is_asked_and_the_answer_completes_it(
    flat: KB, text: str, asked: str, answer: str, roles: dict[str, str]
) -> None:
    out = say(flat, text, LEON)
    assert out.intent is None and out.clarify and out.reply.startswith(asked)
    done = say(flat, answer, LEON, [("user", text), ("robot", out.reply)])
    assert done.roles == roles, done.reply


def test_a_word_heard_wrong_or_said_short_is_the_one_thing_it_fits_a_guess(flat: KB) -> None:
    picks = say(flat, "bring me the guitar pics", LEON)
    assert picks.roles == {"object": "picks_1", "recipient": LEON} and picks.guessed
    mic = say(flat, "pass me the mic", LEON)
    assert mic.roles == {"object": "mic_1", "recipient": LEON} and mic.guessed
    assert say(flat, "pass me the to", LEON).intent is None  # too short to be said short for anything


def test_its_owner_is_whom_the_kb_says_the_thing_belongs_to(flat: KB) -> None:
    flat.update(["mic_1 belongsTo person_dana"])
    out = say(flat, "grab the microphone and give it to its owner")
    assert [(o.intent, o.roles) for o in out.steps()][-1] == (
        I.BRING_OBJECT, {"object": "mic_1", "recipient": "person_dana"})
    out = say(flat, "bring the guitar picks to their owner")  # the KB says of no owner: no guess
    assert out.intent is None and out.more == ()


def test_a_thing_returned_to_its_owner_is_brought_to_them_not_put_somewhere(flat: KB) -> None:
    flat.update(["mic_1 belongsTo person_dana"])
    out = say(flat, "could you return the microphone to its owner?", LEON)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "mic_1", "recipient": "person_dana"})


@pytest.mark.parametrize(
    "text",
    ["bring the microphone to the lounge for Dana", "bring the microphone to Dana in the lounge",
     "take the microphone over to the lounge for Dana"],
)  # fmt: skip
def test_a_recipient_said_with_where_they_are_is_the_person(flat: KB, text: str) -> None:
    out = say(flat, text)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "mic_1", "recipient": "person_dana"})


def test_a_place_said_alone_is_still_where_to_bring(flat: KB) -> None:
    out = say(flat, "bring the microphone to the bathroom")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "mic_1", "recipient": "bathroom"})


def test_a_head_noun_known_only_inside_other_names_is_not_understood(flat: KB) -> None:
    # "bread" names nothing here by itself, only the bread shelf: the loaf may be what is meant
    flat.update(["shelf_b rdf:type Artifact", 'shelf_b rdfs:label "bread shelf"', "shelf_b isIn lounge",
                 "loaf_1 rdf:type Artifact", 'loaf_1 rdfs:label "sourdough loaf"', "loaf_1 isOn shelf_b"])  # fmt: skip
    out = say(flat, "grab the bread that's on the bread shelf", LEON)
    assert out.intent is None and not out.understood
    # a head noun that names things, none of them fitting, is answered
    out = say(flat, "grab the microphone on the stool", LEON)
    assert out.understood and "don't see any microphone" in out.reply


def test_of_several_things_the_one_the_robot_just_named_is_meant(flat: KB) -> None:
    flat.add(["towel_g rdf:type Cloth", 'towel_g rdfs:label "beach towel"', "towel_g isIn bathroom"])
    listed = [("user", "what's in the bathroom"), ("robot", "A beach towel and a stool.")]
    out = say(flat, "give me the towel", LEON, listed)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "towel_g", "recipient": LEON}), out.reply
    # the robot named both, or spoke of neither, or the person spoke last: which one is asked
    for history in ([("robot", "There is a beach towel and a towel.")], [("robot", "A stool.")],
                    [*listed, ("user", "thanks")]):  # fmt: skip
        assert say(flat, "give me the towel", LEON, history).clarify, history


def test_a_place_said_with_where_it_is_is_that_place(office: KB) -> None:
    for text in ("put the pear on the desk in the office", "put the pear on the desk out in the office"):
        assert say(office, text).roles == {"object": "pear_1", "recipient": "desk_1"}
    # next to a thing that is not on it, the last place is where to put it
    assert say(office, "put the pear next to the laptop on the desk").roles["recipient"] == "desk_1"


def test_a_pronoun_where_a_thing_is_put_is_the_place_last_spoken_of(flat: KB) -> None:
    history = [("user", "put the microphone on the standing desk"),
               ("robot", "OK, I've put the microphone on the standing desk.")]  # fmt: skip
    out = say(flat, "and put the guitar picks next to it", speaker=LEON, history=history)
    assert (out.intent, out.roles) == (I.PLACE_OBJECT, {"object": "picks_1", "recipient": "desk_2"}), out.reply
    # the thing put is still the thing spoken of: "pick it up" is the microphone
    assert say(flat, "now pick it up", speaker=LEON, history=history).roles == {"object": "mic_1"}
