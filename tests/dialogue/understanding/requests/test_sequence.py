"""A compound request read part by part: what cannot be done is said, what is carried on is taken."""

import pytest

from dialogue import intents as I
from kb import KB
from tests.dialogue.understanding.test_interpret import BOB, say


def test_a_part_the_robot_has_no_intent_for_does_not_sink_the_others(office: KB) -> None:
    out = say(office, "go to the desk and count the staplers")
    assert [(o.intent, o.roles) for o in out.steps()] == [(I.MOVE_TO, {"goal": "desk_1"})]
    assert "can't count the staplers" in out.reply


def test_a_question_after_an_action_is_not_answered_now(office: KB) -> None:
    out = say(office, "go to the desk and tell me what is on it")
    assert [o.intent for o in out.steps()] == [I.MOVE_TO]
    assert "can't tell you what is on it" in out.reply  # said back to the speaker


@pytest.mark.parametrize(
    "text", ["fetch the pear from the desk and give it to Carol", "get the pear off the desk and hand it to Carol",
             "Fetch the pear and then take it to Carol."],
)  # fmt: skip
def test_a_thing_fetched_and_handed_on_to_someone_is_one_bringing(office: KB, text: str) -> None:
    out = say(office, text)
    assert [(o.intent, o.roles) for o in out.steps()] == [
        (I.BRING_OBJECT, {"object": "pear_1", "recipient": "person_carol"})]
    assert out.reply == "OK, I will bring the pear to Carol."


@pytest.mark.parametrize("text", ["pick up the pear and give it to Carol", "grab the pear, then bring it to Carol"])
def test_a_thing_taken_and_handed_on_is_taken_first(office: KB, text: str) -> None:
    out = say(office, text)
    assert [(o.intent, o.roles) for o in out.steps()] == [
        (I.GRAB_OBJECT, {"object": "pear_1"}),
        (I.BRING_OBJECT, {"object": "pear_1", "recipient": "person_carol"}),
    ]
    assert out.reply.startswith("OK, I will pick up the pear.")


def test_a_thing_fetched_and_put_somewhere_is_taken_first(office: KB) -> None:
    out = say(office, "fetch the pear and put it on the desk")
    assert [o.intent for o in out.steps()] == [I.GRAB_OBJECT, I.PLACE_OBJECT]


def test_a_thing_fetched_for_the_speaker_alone_is_brought(office: KB) -> None:
    out = say(office, "fetch the pear and go to the desk")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "pear_1", "recipient": BOB})


def test_retrieve_and_remove_take_a_thing(office: KB) -> None:
    for verb in ("retrieve", "remove"):
        out = say(office, f"{verb} the stapler from the desk and put it on the shelf")
        assert [o.intent for o in out.steps()] == [I.GRAB_OBJECT, I.PLACE_OBJECT]


def test_a_thing_wished_for_then_asked_to_be_taken_is_brought_to_whoever_wished(office: KB) -> None:
    for text in ("I want the pear, can you get it", "I want the pear. Can you get it?"):
        out = say(office, text)
        assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "pear_1", "recipient": BOB})
    out = say(office, "Carol needs the stapler, could you grab it")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "stapler_1", "recipient": "person_carol"})
    # with no wish before it, taking is taking
    assert say(office, "the stapler, can you grab it").intent == I.GRAB_OBJECT


def test_the_other_request_forms(office: KB) -> None:
    assert say(office, "let's go to the bathroom").roles == {"goal": "bathroom"}
    assert say(office, "catch the pear").intent == I.GRAB_OBJECT
    assert (say(office, "get the pear from the desk").intent) == I.GRAB_OBJECT
    out = say(office, "At the desk, bring Carol the pear")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "pear_1", "recipient": "person_carol"})
    out = say(office, "dear robot, bring me the pear")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "pear_1", "recipient": BOB})
    out = say(office, "Carol is sitting by the desk, could you bring her the pear")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "pear_1", "recipient": "person_carol"})


def test_going_to_someone_and_then_engaging_with_them_is_the_engaging(office: KB) -> None:
    for text in ("go over to Carol and have a chat with her", "go to Carol and keep her company"):
        out = say(office, text)
        assert [(o.intent, o.roles) for o in out.steps()] == [(I.ENGAGE_WITH, {"recipient": "person_carol"})]
    # going somewhere else first is two steps
    out = say(office, "go to the desk and talk to Carol")
    assert [o.intent for o in out.steps()] == [I.MOVE_TO, I.ENGAGE_WITH]


def test_a_thing_someone_would_like_brought_with_no_one_said_is_brought_to_them(office: KB) -> None:
    out = say(office, "Carol would like the stapler, please bring it")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "stapler_1", "recipient": "person_carol"})
    # said to whom, it goes there
    out = say(office, "Carol would like the stapler, please bring it to me")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "stapler_1", "recipient": BOB})


def test_a_part_beyond_the_robots_skills_does_not_sink_the_others(office: KB) -> None:
    out = say(office, "pick up the pear and iron it")
    assert [(o.intent, o.roles) for o in out.steps()] == [(I.GRAB_OBJECT, {"object": "pear_1"})]
    assert out.reply == "OK, I will pick up the pear. I can't iron it myself."


def test_a_question_with_a_verb_after_and_is_one_question(office: KB) -> None:
    out = say(office, "now then, where have they gone and put the pear?")
    assert out.intent is None and not out.clarify and "desk" in out.reply


@pytest.mark.parametrize(
    "text",
    ["the stapler is mine, you can give to me?", "the stapler is mine. could you bring to me", "I like the stapler, give me"],
)
def test_a_thing_left_out_after_a_clause_that_names_it_is_that_thing(office: KB, text: str) -> None:
    out = say(office, text)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "stapler_1", "recipient": BOB})


def test_a_thing_left_out_with_no_thing_named_before_is_asked_for(office: KB) -> None:
    for text in ("Carol is here, give to me", "give to me"):
        out = say(office, text)
        assert out.intent is None and out.clarify, text


@pytest.mark.parametrize("text", ["leave it there and bring me the pear", "ok, leave it there, then bring me the pear"])
def test_a_thing_left_where_it_is_does_not_sink_the_parts_after_it(office: KB, text: str) -> None:
    history = [("user", "where is the laptop?"), ("robot", "On the desk.")]
    out = say(office, text, history=history)
    assert [(o.intent, o.roles) for o in out.steps()] == [(I.BRING_OBJECT, {"object": "pear_1", "recipient": BOB})]
    assert out.reply == "OK, I will leave it where it is. OK, I will bring the pear to you."
