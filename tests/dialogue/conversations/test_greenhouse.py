"""Issue 30, the classes of its third round, in a greenhouse: corrections in a row, "both" and
things named in turn in the order said, "the left one" where the KB says which is left; following,
waiting for and staying with someone else; people as they or by name; what the robot can do, help
and jokes."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from dialogue import intents as I
from tests.dialogue.conversations.talk import Said, Talk, talking

GREENHOUSE = [
    "myself rdf:type Robot",
    'greenhouse rdf:type ZoneOfInterest', 'greenhouse rdfs:label "greenhouse"',
    'potting_shed rdf:type ZoneOfInterest', 'potting_shed rdfs:label "potting shed"',
    'person_ilse rdf:type Human', 'person_ilse rdfs:label "Ilse"', "person_ilse isIn greenhouse",
    "myself sees person_ilse",
    'person_bram rdf:type Human', 'person_bram rdfs:label "Bram"', "person_bram isIn greenhouse",
    "myself sees person_bram",
    'person_wren rdf:type Human', 'person_wren rdfs:label "Wren"', "person_wren isIn potting_shed",
    'trestle_1 rdf:type Table', 'trestle_1 rdfs:label "trestle"', "trestle_1 isIn greenhouse",
    "myself sees trestle_1",
    'can_g rdf:type Container', 'can_g rdfs:label "watering can"', "can_g hasColor green", "can_g isOn trestle_1",
    "myself sees can_g",
    'can_r rdf:type Container', 'can_r rdfs:label "watering can"', "can_r hasColor red", "can_r isOn trestle_1",
    "myself sees can_r",
    "can_g leftOf can_r",
    'pot_1 rdf:type Container', 'pot_1 rdfs:label "pot"', "pot_1 hasColor terracotta", "pot_1 isOn trestle_1",
    "myself sees pot_1",
    'pot_2 rdf:type Container', 'pot_2 rdfs:label "pot"', "pot_2 hasColor white", "pot_2 isOn trestle_1",
    "myself sees pot_2",
]  # fmt: skip

ILSE, BRAM, WREN = "person_ilse", "person_bram", "person_wren"


@pytest.fixture
def talk() -> Iterator[Talk]:
    with talking(GREENHOUSE, ILSE) as talk:
        yield talk


def _bring(thing: str, to: str = ILSE) -> tuple[str, dict[str, object]]:
    return (I.BRING_OBJECT, {"object": thing, "recipient": to})


def test_a_second_correction_in_a_row_corrects_the_first(talk: Talk) -> None:
    assert talk("hand me the green watering can").intents == (_bring("can_g"),)
    assert talk("no, the red one") == Said("OK, I will bring the red watering can to you.", (_bring("can_r"),))
    assert talk("no, the other one") == Said("OK, I will bring the green watering can to you.", (_bring("can_g"),))
    said = talk("sorry, I meant to Bram")  # the thing as corrected, to someone else
    assert said == Said("OK, I will bring the green watering can to Bram.", (_bring("can_g", BRAM),))
    assert talk("no, the red one").intents == (_bring("can_r", BRAM),)


def test_both_and_things_named_in_turn_keep_their_order(talk: Talk) -> None:
    asked = talk("pass me the pot").reply
    assert asked == "Which pot do you mean: the terracotta one or the white one?"
    said = talk("the white one and then the terracotta one")  # the order the person says
    assert said.intents == (_bring("pot_2"), _bring("pot_1"))
    assert said.reply == "OK, I will bring the white pot to you. Then I will bring the terracotta pot to you."
    talk("pass me the pot")
    assert talk("both of them").intents == (_bring("pot_1"), _bring("pot_2"))  # the order the robot listed


def test_the_left_one_where_the_kb_says_and_unknown_where_it_does_not(talk: Talk) -> None:
    talk("pass me the watering can")
    assert talk("the one on the left") == Said("OK, I will bring the green watering can to you.", (_bring("can_g"),))
    talk("pass me the watering can")
    assert talk("the right one").intents == (_bring("can_r"),)
    asked = talk("pass me the pot").reply  # nothing said of the pots' sides
    said = talk("the left one")
    assert said == Said(f"Sorry, I can't tell which one is the left one. {asked}", ())
    # where each is, said by which the other is
    assert "to the right of the green watering can" in talk("where is the red watering can?").reply


def test_following_waiting_for_and_staying_with_someone(talk: Talk) -> None:
    follow = (I.START_ACTIVITY, {"object": "follow", "recipient": BRAM})
    assert talk("could you follow Bram?") == Said("OK, I will follow Bram.", (follow,))
    assert talk("follow me instead").intents == ((I.START_ACTIVITY, {"object": "follow", "recipient": ILSE}),)
    for waiting in ("wait for me", "please wait for Wren"):
        assert talk(waiting) == Said("OK, I am stopping.", ((I.STOP_ACTIVITY, {}),))
    assert talk("stay with Bram") == Said("OK, I will go and talk to Bram.", ((I.ENGAGE_WITH, {"recipient": BRAM}),))
    assert talk("stay with me") == Said("OK, I'm here with you.", ((I.ENGAGE_WITH, {"recipient": ILSE}),))


def test_people_are_they_or_their_name_never_it(talk: Talk) -> None:
    # the ontology (nor knowledge_core's ORO) says nobody's gender: they, or the name
    said = talk("where is Wren?").reply
    assert said == "Wren is in the potting shed. I don't see them right now."
    assert " it " not in f" {talk('is Wren in the greenhouse?').reply} "


def test_help_jokes_and_what_the_robot_can_do(talk: Talk) -> None:
    can = talk("what can you do?")
    assert can.intents == () and can.reply.startswith("I can go and talk to someone, go places, take people")
    assert "follow people" in can.reply
    assert talk("help").reply == can.reply
    assert talk("tell me a joke") == Said("I'm afraid I don't know any jokes: ask me to fetch something instead!", ())
