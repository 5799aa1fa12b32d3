"""Compound requests: cut into parts in order, each part read with the earlier ones as context."""

import pytest

from dialogue import intents as I
from dialogue.understanding.requests import compound
from dialogue.understanding.requests.compound import Part
from kb import KB
from tests.dialogue.conftest import english, scene_kb
from tests.dialogue.understanding.test_interpret import say


def conjuncts(text: str) -> list[Part]:
    return compound.conjuncts(english(), text)


@pytest.mark.parametrize(
    ("text", "parts"),
    [
        ("go to the kitchen and take the plate", ["go to the kitchen", "take the plate"]),
        ("take the book, then put it in the oven", ["take the book", "put it in the oven"]),
        ("go to the bathroom take the rag", ["go to the bathroom", "take the rag"]),
        ("go to the sofa and search for the pillow", ["go to the sofa", "search for the pillow"]),
        ("bring me the cereals and the milk", []),  # one command, two things
        # a part with no verb that says the request before it again for another thing: that verb
        ("bring the tea to Ana and then the bun to Bo", ["bring the tea to Ana", "bring the bun to Bo"]),
        ("could you put the cup on the shelf please, and the plate on the table",
         ["could you put the cup on the shelf please", "put the plate on the table"]),
        ("bring the tea and the bun to Bo", []),  # one request of two things
        ("take the tea to Bo, he has to sign for it", []),  # a remark after it
        ("put the salt and pepper on the table", []),
        ('say "stop and wait" to Carol', []),  # a quotation is one text
        ("go get a book for me", []),
        # "go" before a verb starts a request after a remark; a verb after a modal is the remark's own
        ("omar is at the door go say hi to him", ["omar is at the door", "go say hi to him"]),
        ("mia can't find her pen, can you take it to her", ["mia can't find her pen", "can you take it to her"]),
        ("omar is in the shed tell him lunch is ready", ["omar is in the shed", "tell him lunch is ready"]),
        # "and" as chat writes it; other chat words cut nothing ("cn u go...": "u" is "you")
        ("fetch the tray n put it on the shelf", ["fetch the tray", "put it on the shelf"]),
        # a verb after a subject with its auxiliary says what they did or will do: no command
        ("I've put the keys by the kettle", []),
        ("I'll take the orange juice, ta", []),
        ("cn u go to the shed", ["cn u", "go to the shed"]),
        # an action the robot has no intent for is a part of its own, kept in the reply
        ("go to the shed and see if the hose is there", ["go to the shed", "see if the hose is there"]),
        # a greeting asked for after a remark
        ("ola is here say hi", ["ola is here", "say hi"]),
        # a verb no frame knows, said before what it is done to, starts a part of its own
        ("take the pear and inspect it", ["take the pear", "inspect it"]),
        ("go to the hall and count the chairs", ["go to the hall", "count the chairs"]),
        # a noun after "and" does not ("plate" is a verb too, but nothing follows it)
        ("bring me the fork and plate", []),
        ("put the mug and saucer on the tray", []),
        # a phrase that says the order opens the later part, which is a request of its own
        ("take the pear, and after that go to the desk", ["take the pear", "after that go to the desk"]),
        # a verb with nothing said after its preposition starts no request ("get to": went)
        ("where did the ball of twine get to", []),
        # a verb after a subject, a modal and an adverb is that clause's own
        ("pick up the sheet. I'd only put my back out", []),
    ],
)
def test_parts(text: str, parts: list[str]) -> None:
    assert [p.text for p in conjuncts(text)] == parts


def test_every_intent_in_order_with_pronouns_across_parts(office: KB) -> None:
    out = say(office, "take the stapler and put it on the shelf")
    assert [(o.intent, o.roles) for o in out.steps()] == [
        (I.GRAB_OBJECT, {"object": "stapler_1"}),
        (I.PLACE_OBJECT, {"object": "stapler_1", "recipient": "shelf_9"}),
    ]
    assert "stapler" in out.reply and out.reply.count("OK") == 1


def test_a_part_opened_by_after_that_is_done_not_dropped(office: KB) -> None:
    out = say(office, "take Carol to the bathroom, and once that is done bring me the pear")
    assert [(o.intent, o.roles) for o in out.steps()] == [
        (I.GUIDE, {"recipient": "person_carol", "goal": "bathroom"}),
        (I.BRING_OBJECT, {"object": "pear_1", "recipient": "person_bob"}),
    ]


def test_three_parts_without_conjunctions(office: KB) -> None:
    out = say(office, "go to the desk take the pear and bring it to Carol")
    assert [o.intent for o in out.steps()] == [I.MOVE_TO, I.GRAB_OBJECT, I.BRING_OBJECT]
    assert out.steps()[2].roles == {"object": "pear_1", "recipient": "person_carol"}


def test_a_part_with_no_intent_is_kept_in_the_reply(office: KB) -> None:
    out = say(office, "go to the desk and look for the umbrella")
    assert [o.intent for o in out.steps()] == [I.MOVE_TO]
    assert "look for the umbrella" in out.reply and out.understood


def test_a_part_that_fails_says_why_and_nothing_is_done(office: KB) -> None:
    out = say(office, "take the stapler and lift the desk")
    assert out.intent is None and out.more == () and "can't move the desk" in out.reply
    # a part whose words the KB names nothing with makes the whole not understood
    out = say(office, "take the stapler and put it on the moon")
    assert out.intent is None and out.more == () and not out.understood


def test_an_ambiguous_part_is_asked_about_first(office: KB) -> None:
    out = say(office, "go to the desk and take the mug")
    assert out.clarify and out.intent is None and "Which" in out.reply


def test_coordinated_things_are_one_intent_each(office: KB) -> None:
    out = say(office, "pick up the stapler and the pear")
    assert [(o.intent, o.roles) for o in out.steps()] == [
        (I.GRAB_OBJECT, {"object": "stapler_1"}),
        (I.GRAB_OBJECT, {"object": "pear_1"}),
    ]


def test_a_greeting_before_a_compound_is_context(office: KB) -> None:
    out = say(office, "hi there, go to the desk and take the pear")
    assert [o.intent for o in out.steps()] == [I.MOVE_TO, I.GRAB_OBJECT]


def test_a_greeting_before_the_first_command_keeps_the_command(office: KB) -> None:
    out = say(office, "hey robot take the stapler and put it on the shelf")
    assert [o.intent for o in out.steps()] == [I.GRAB_OBJECT, I.PLACE_OBJECT]


def test_a_part_that_only_says_where_not_to_be_is_an_aside() -> None:
    parts = conjuncts("could you get out of the way and go to the shelf")
    assert [(p.text, p.aside) for p in parts] == [("could you get out of the way", True), ("go to the shelf", False)]
    assert not any(p.aside for p in conjuncts("get the stapler and go to the shelf"))


def test_a_part_asking_for_a_state_is_kept_in_the_reply(office: KB) -> None:
    parts = conjuncts("go to the bathroom and get it ready")
    assert [p.no_intent for p in parts] == [False, True]
    out = say(office, "go too the bathroom and get it ready")
    assert (out.intent, out.roles) == (I.MOVE_TO, {"goal": "bathroom"}) and "can't get it ready" in out.reply


def test_a_part_whose_verb_no_frame_knows_is_one_the_robot_cannot_do() -> None:
    parts = conjuncts("greet Ana and offer her a coffee")
    assert [(p.verb, p.no_intent) for p in parts] == [("greet", False), ("offer", True)]


@pytest.mark.parametrize("joint", [" and then ", ", then ", " please, and "])
def test_a_request_said_again_for_another_thing_without_its_verb_is_both(office: KB, joint: str) -> None:
    out = say(office, f"could you bring the pear to Carol{joint}the stapler to Dan")
    assert [(o.intent, o.roles) for o in out.steps()] == [
        (I.BRING_OBJECT, {"object": "pear_1", "recipient": "person_carol"}),
        (I.BRING_OBJECT, {"object": "stapler_1", "recipient": "person_dan"}),
    ]


def _study() -> KB:
    return scene_kb(
        None, "myself rdf:type Robot", "person_bob rdf:type Human", 'person_bob rdfs:label "Bob"',
        "pills rdf:type Box", 'pills rdfs:label "painkillers"', "myself sees pills",
        "glass rdf:type Glass", 'glass rdfs:label "glass of water"', "myself sees glass",
        "mill rdf:type Artifact", 'mill rdfs:label "salt and pepper mill"', "myself sees mill",
        "salt rdf:type Artifact", 'salt rdfs:label "salt"', "myself sees salt",
    )  # fmt: skip


@pytest.mark.parametrize(
    ("text", "objects"),
    [
        # a name found inside "X and Y" is one of two things, not all that was asked for
        ("bring me the painkillers and the glass of water", ["pills", "glass"]),
        ("bring me the painkillers please and then the glass of water", ["pills", "glass"]),
        ("painkillers please and then the glass of water", ["pills", "glass"]),  # said without a verb
        ("the glass of water and the painkillers, please", ["glass", "pills"]),
        # a name that says "and" itself is one thing
        ("bring me the salt and pepper mill", ["mill"]),
    ],
)
def test_two_things_joined_by_and_are_each_brought(text: str, objects: list[str]) -> None:
    out = say(_study(), text, speaker="person_bob")
    assert [o.roles["object"] for o in out.steps()] == objects
    assert {o.intent for o in out.steps()} == {I.BRING_OBJECT}
