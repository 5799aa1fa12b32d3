"""Answers to the robot's last question: fragments, confirmations and accepted offers."""

import pytest

from dialogue import intents as I
from kb import KB
from tests.dialogue.conftest import scene_kb
from tests.dialogue.understanding.test_interpret import say

ANA = "person_ana"


@pytest.fixture
def workshop() -> KB:
    return scene_kb(
        None,
        "myself rdf:type Robot",
        "shed rdf:type ZoneOfInterest", 'shed rdfs:label "shed"',
        "porch rdf:type ZoneOfInterest", 'porch rdfs:label "porch"',
        f"{ANA} rdf:type Human", f'{ANA} rdfs:label "Ana"', f"myself sees {ANA}",
        "person_raf rdf:type Human", 'person_raf rdfs:label "Raf"', "myself sees person_raf",
        "saw_1 rdf:type Artifact", 'saw_1 rdfs:label "hand saw"', "myself sees saw_1",
        "saw_2 rdf:type Artifact", 'saw_2 rdfs:label "coping saw"', "myself sees saw_2",
        "saw_3 rdf:type Artifact", 'saw_3 rdfs:label "bow saw"', "myself sees saw_3",
        "cap_1 rdf:type Cloth", 'cap_1 rdfs:label "cap"', "cap_1 hasColor red", "cap_1 belongsTo person_raf",
        "myself sees cap_1",
        "cap_2 rdf:type Cloth", 'cap_2 rdfs:label "cap"', "cap_2 hasColor grey", f"cap_2 belongsTo {ANA}",
        "myself sees cap_2",
        "rake_1 rdf:type Artifact", 'rake_1 rdfs:label "rake"', "myself sees rake_1",
    )  # fmt: skip


def test_no_the_other_one_is_the_one_thing_the_guess_was_not(workshop: KB) -> None:
    workshop.remove(["saw_3 rdf:type Artifact", 'saw_3 rdfs:label "bow saw"', "myself sees saw_3"])  # two saws
    history = [("user", "pass me the saw"), ("robot", "Do you mean the hand saw?")]
    out = say(workshop, "no, the other one", speaker=ANA, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "saw_2", "recipient": ANA})
    out = say(workshop, "yes that one", speaker=ANA, history=history)
    assert out.roles == {"object": "saw_1", "recipient": ANA}


def test_the_other_one_of_three_is_not_known(workshop: KB) -> None:
    history = [("user", "pass me the saw"), ("robot", "Do you mean the hand saw?")]
    assert say(workshop, "no the other one", speaker=ANA, history=history).intent is None


@pytest.mark.parametrize(
    ("offer", "answer", "intent", "roles"),
    [
        ("Shall I fetch you the rake?", "yes please", I.BRING_OBJECT, {"object": "rake_1", "recipient": ANA}),
        ("Would you like me to take you to the porch?", "ok that'd be lovely", I.GUIDE,
         {"recipient": ANA, "goal": "porch"}),
        ("Would you like the rake?", "yeah", I.BRING_OBJECT, {"object": "rake_1", "recipient": ANA}),
    ],
)  # fmt: skip
def test_an_accepted_offer_is_the_request_offered(
    workshop: KB, offer: str, answer: str, intent: str, roles: dict[str, str]
) -> None:
    out = say(workshop, answer, speaker=ANA, history=[("user", "my hands are cold"), ("robot", offer)])
    assert (out.intent, out.roles) == (intent, roles)


def test_a_declined_offer_does_nothing(workshop: KB) -> None:
    history = [("user", "my hands are cold"), ("robot", "Shall I fetch you the rake?")]
    assert say(workshop, "no thanks", speaker=ANA, history=history).intent is None


@pytest.mark.parametrize("answer", ["the red one, it's Raf's", "the red one its Raf's", "the grey one it's mine"])
def test_a_fragment_may_say_whose_the_thing_is(workshop: KB, answer: str) -> None:
    history = [("user", "grab the cap"), ("robot", "Which cap do you mean: the red one or the grey one?")]
    out = say(workshop, answer, speaker=ANA, history=history)
    assert out.intent == I.GRAB_OBJECT and out.roles["object"] == ("cap_2" if "mine" in answer else "cap_1")


@pytest.mark.parametrize("answer", ["go on then", "yeah go ahead", "ok that would be lovely", "why not"])
def test_an_offer_is_accepted_in_words_that_would_be_a_request_of_their_own(workshop: KB, answer: str) -> None:
    # "go on then" is no going anywhere after "Shall I...?"
    history = [("user", "my hands are cold"), ("robot", "Shall I fetch you the rake?")]
    out = say(workshop, answer, speaker=ANA, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "rake_1", "recipient": ANA})


def test_nope_the_other_one(workshop: KB) -> None:
    workshop.remove(["saw_3 rdf:type Artifact", 'saw_3 rdfs:label "bow saw"', "myself sees saw_3"])
    history = [("user", "grab the saw"), ("robot", "Did you mean the coping saw?")]
    assert say(workshop, "nope, the other one", speaker=ANA, history=history).roles == {"object": "saw_1"}


def test_a_fragment_may_say_it_is_the_speakers_without_punctuation(workshop: KB) -> None:
    history = [("user", "grab the cap"), ("robot", "Which cap do you mean: the red one or the grey one?")]
    assert say(workshop, "the grey one its mine", speaker=ANA, history=history).roles == {"object": "cap_2"}


@pytest.mark.parametrize(
    ("answer", "roles"),
    [
        ("sorry I meant the porch", {"object": "rake_1", "recipient": "porch"}),  # the place, not the rake
        ("oops i meant the hand saw", {"object": "saw_1", "recipient": "shed"}),  # the thing, not the shed
        ("no sorry, I mean the bow saw", {"object": "saw_3", "recipient": "shed"}),
        ("I meant to the porch", {"object": "rake_1", "recipient": "porch"}),
    ],
)
def test_a_correction_redoes_the_last_request_with_what_was_meant(
    workshop: KB, answer: str, roles: dict[str, str]
) -> None:
    history = [("user", "take the rake to the shed"), ("robot", "OK, I will bring the rake to the shed.")]
    out = say(workshop, answer, speaker=ANA, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, roles), out.reply


def test_a_correction_says_the_same_kind_of_thing_as_what_it_corrects(workshop: KB) -> None:
    history = [("user", "take the rake to the shed"), ("robot", "OK, I will bring the rake to the shed.")]
    # Raf is neither a place nor a thing to carry: nothing to correct
    assert say(workshop, "sorry I meant Raf", speaker=ANA, history=history).intent is None
    # with no request before it, "I meant the porch" corrects nothing
    assert not say(workshop, "I meant the porch", speaker=ANA).understood


@pytest.mark.parametrize("answer", ["not the shed, the porch", "the porch, not the shed", "no not the shed the porch"])
def test_not_this_but_that_corrects_the_last_request(workshop: KB, answer: str) -> None:
    history = [("user", "take the rake to the shed"), ("robot", "OK, I will bring the rake to the shed.")]
    out = say(workshop, answer, speaker=ANA, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "rake_1", "recipient": "porch"}), out.reply


def test_a_correction_and_an_answer_complete_a_request_said_without_to(workshop: KB) -> None:
    # "fetch the saw": to whom is not said ("fetch Ana the saw" would say it), yet the answer to
    # "Which saw?" and a correction keep the request's own recipient
    asked = [("user", "fetch the saw"), ("robot", "Which saw do you mean: the hand saw, the coping saw or the bow saw?")]
    out = say(workshop, "the bow one", speaker=ANA, history=asked)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "saw_3", "recipient": ANA}), out.reply
    done = [("user", "fetch the hand saw"), ("robot", "OK, I will bring the hand saw to you.")]
    out = say(workshop, "sorry I meant the coping one", speaker=ANA, history=done)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "saw_2", "recipient": ANA}), out.reply


@pytest.mark.parametrize(
    "said", ["and the rake goes to the porch", "and uh the rake goes to the porch please", "and then the rake to the porch"]
)
def test_the_same_request_for_another_thing_and_place(workshop: KB, said: str) -> None:
    history = [("user", "take the hand saw to the shed"), ("robot", "OK, I will bring the hand saw to the shed.")]
    out = say(workshop, said, speaker=ANA, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "rake_1", "recipient": "porch"})
    out = say(workshop, "the rake goes to Raf", speaker=ANA, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "rake_1", "recipient": "person_raf"})


@pytest.mark.parametrize(
    "history",
    [[], [("user", "go to the shed"), ("robot", "OK, I am going to the shed.")]],
)
def test_where_a_thing_goes_is_no_bringing_after_no_bringing(workshop: KB, history: list[tuple[str, str]]) -> None:
    # "the rake goes to the porch" alone says where it belongs, not what to do: left to a model
    out = say(workshop, "the rake goes to the porch", speaker=ANA, history=history)
    assert out.intent is None and not out.understood


@pytest.mark.parametrize("answer", ["hmm no, the other one", "no sorry the other one", "the other one"])
def test_the_other_one_after_a_request_is_the_one_other_thing_its_head_names(workshop: KB, answer: str) -> None:
    history = [("user", "bring me the red cap"), ("robot", "OK, I will bring the cap to you.")]
    out = say(workshop, answer, speaker=ANA, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "cap_2", "recipient": ANA}), out.reply
    # three saws: which other one is not known
    history = [("user", "bring me the hand saw"), ("robot", "OK, I will bring the hand saw to you.")]
    assert say(workshop, answer, speaker=ANA, history=history).intent is None


def test_no_and_a_description_corrects_the_thing_just_asked_for(workshop: KB) -> None:
    history = [("user", "hand me Raf's cap"), ("robot", "OK, I will bring Raf's cap to you.")]
    for answer in ("no, the grey one", "nope, the grey one!"):
        out = say(workshop, answer, speaker=ANA, history=history)
        assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "cap_2", "recipient": ANA})
    assert say(workshop, "the grey one", speaker=ANA, history=history).intent is None  # no "no": no correction
    # a correction never makes one thing both roles: the red cap put on the red cap
    history = [("user", "put the grey cap on the rake"), ("robot", "OK, I will put the grey cap on the rake.")]
    assert say(workshop, "no, the grey one", speaker=ANA, history=history).intent is None


def test_both_is_the_request_for_each_thing_asked_about(workshop: KB) -> None:
    history = [("user", "pick up the cap"), ("robot", "Which cap do you mean: the grey one or the red one?")]
    out = say(workshop, "both please", speaker=ANA, history=history)
    assert [(o.intent, o.roles) for o in out.steps()] == [(I.GRAB_OBJECT, {"object": "cap_2"}),
                                                          (I.GRAB_OBJECT, {"object": "cap_1"})]
    assert out.reply == "OK, I will pick up the grey cap. Then I will pick up the red cap."


def test_an_answer_after_the_question_was_asked_again_completes_the_request(workshop: KB) -> None:
    question = "Which cap do you mean: the grey one or the red one?"
    history = [("user", "pick up the cap"), ("robot", question), ("user", "the left one"),
               ("robot", f"Sorry, I can't tell which one is the left one. {question}")]
    assert say(workshop, "the red one", speaker=ANA, history=history).roles == {"object": "cap_1"}
    # another question in between: the old request is no longer pending
    history[3] = ("robot", "Where should I put it?")
    assert say(workshop, "the red one", speaker=ANA, history=history).intent is None


def test_both_is_each_thing_in_the_order_the_question_listed_them(workshop: KB) -> None:
    for listed, order in (("the red one or the grey one", ["cap_1", "cap_2"]),
                          ("the grey one or the red one", ["cap_2", "cap_1"])):  # fmt: skip
        history = [("user", "grab the cap"), ("robot", f"Which cap do you mean: {listed}?")]
        out = say(workshop, "both please", speaker=ANA, history=history)
        assert [o.roles["object"] for o in out.steps()] == order, out.reply


def test_things_named_one_after_another_are_each_meant_in_that_order(workshop: KB) -> None:
    history = [("user", "grab the cap"), ("robot", "Which cap do you mean: the red one or the grey one?")]
    out = say(workshop, "the grey one and then the red one", speaker=ANA, history=history)
    assert [(o.intent, o.roles) for o in out.steps()] == [(I.GRAB_OBJECT, {"object": "cap_2"}),
                                                          (I.GRAB_OBJECT, {"object": "cap_1"})]  # fmt: skip
    assert out.reply == "OK, I will pick up the grey cap. Then I will pick up the red cap."
    # the same one twice is not two things
    assert len(say(workshop, "the red one and the red one", speaker=ANA, history=history).steps()) == 1


def test_the_left_one_is_the_one_the_kb_puts_left_of_the_others(workshop: KB) -> None:
    question = "Which cap do you mean: the grey one or the red one?"
    history = [("user", "pick up the cap"), ("robot", question)]
    workshop.add(["cap_1 leftOf cap_2"])  # as the robot sees them; the reasoner adds cap_2 rightOf cap_1
    assert say(workshop, "the left one", speaker=ANA, history=history).roles == {"object": "cap_1"}
    assert say(workshop, "the one on the right", speaker=ANA, history=history).roles == {"object": "cap_2"}
    # where each is says which the other is
    reply = say(workshop, "where is the red cap?", speaker=ANA).reply
    assert reply.endswith("to the left of the grey cap."), reply


def test_the_left_one_of_three_needs_one_left_of_every_other(workshop: KB) -> None:
    question = "Which saw do you mean: the hand saw, the coping saw or the bow saw?"
    history = [("user", "pick up the saw"), ("robot", question)]
    workshop.add(["saw_1 leftOf saw_2"])  # nothing said of the bow saw
    out = say(workshop, "the left one", speaker=ANA, history=history)
    assert out.intent is None and out.reply.startswith("Sorry, I can't tell which one is the left one.")
    workshop.add(["saw_3 rightOf saw_2"])  # left of both now, by the relation's transitivity
    assert say(workshop, "the left one", speaker=ANA, history=history).roles == {"object": "saw_1"}


def test_an_answer_with_a_word_the_kb_names_nothing_with_is_not_asked_again(workshop: KB) -> None:
    # "the stripy one": maybe how the speaker tells one of them apart; asking again claims neither fits
    history = [("user", "pick up the cap"), ("robot", "Which cap do you mean: the grey one or the red one?")]
    out = say(workshop, "the stripy one, please", speaker=ANA, history=history)
    assert out.intent is None and not out.understood
    # "the left one", a position the KB says nothing of, is still said so and asked again
    out = say(workshop, "the left one", speaker=ANA, history=history)
    assert out.clarify and "left one" in out.reply


@pytest.mark.parametrize(
    ("asked", "answer"),
    [("Do you mean the rake by the door?", "yes"), ("Shall I fetch the rake for Raf?", "yes go on"),
     ("Raf is in the shed. Shall I take it out there?", "yes, please do")],
)  # fmt: skip
def test_yes_to_another_robots_question_about_a_request_read_whole_is_that_request(
    workshop: KB, asked: str, answer: str
) -> None:
    # (the question is not the one the rules ask: the history comes from another system)
    history = [("user", "take the rake to Raf"), ("robot", asked)]
    out = say(workshop, answer, speaker=ANA, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "rake_1", "recipient": "person_raf"}), asked


def test_yes_to_a_question_naming_what_the_request_did_not_is_not_that_request(workshop: KB) -> None:
    history = [("user", "take the rake to Raf"), ("robot", "Do you mean the red cap?")]
    assert say(workshop, "yes", speaker=ANA, history=history).intent is None
    history = [("user", "take the rake to Raf"), ("robot", "Do you mean the rake? Raf is out.")]
    assert say(workshop, "no", speaker=ANA, history=history).intent is None


def test_an_answer_to_a_question_said_before_other_words_answers_the_question(workshop: KB) -> None:
    history = [("user", "give me the cap"), ("robot", "Do you mean Raf's cap? Yours is the grey one.")]
    out = say(workshop, "no, mine", speaker=ANA, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "cap_2", "recipient": ANA})


def test_yes_to_a_question_that_neither_proposes_nor_confirms_is_not_the_request_again(workshop: KB) -> None:
    history = [("user", "take the rake to Raf"), ("robot", "OK, I'm taking the rake to Raf. Anything else?")]
    assert say(workshop, "yes", speaker=ANA, history=history).intent is None


@pytest.mark.parametrize("asked", ["Is that everything?", "Is that all?", "Is it ok if I do it later?"])
def test_yes_to_a_question_naming_nothing_of_the_request_is_not_that_request_again(
    workshop: KB, asked: str
) -> None:
    history = [("user", "take the rake to Raf"), ("robot", asked)]
    assert say(workshop, "yes", speaker=ANA, history=history).intent is None


def test_an_answer_starting_with_no_is_not_the_request_again(workshop: KB) -> None:
    history = [("user", "take the rake to Raf"), ("robot", "Do you mean the rake by the door?")]
    assert say(workshop, "no, go on", speaker=ANA, history=history).intent is None
