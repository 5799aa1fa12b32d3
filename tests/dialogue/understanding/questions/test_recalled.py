"""Questions about what the robot was asked: said back from the conversation, or said not kept."""

import pytest

from dialogue import intents as I
from dialogue.understanding.interpret import Interpreter
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.questions.recalled import MAX_READ, recalled
from kb import KB
from tests.dialogue.conftest import english, scene_kb
from tests.dialogue.understanding.test_interpret import say

ANA = "person_ana"


@pytest.fixture
def kitchen_table() -> KB:
    return scene_kb(
        None,
        "myself rdf:type Robot",
        f"{ANA} rdf:type Human", f'{ANA} rdfs:label "Ana"', f"myself sees {ANA}",
        "person_bo rdf:type Human", 'person_bo rdfs:label "Bo"', "myself sees person_bo",
        "cup_1 rdf:type dbr:Cup", 'cup_1 rdfs:label "cup"', "myself sees cup_1",
        "pear_1 rdf:type Artifact", 'pear_1 rdfs:label "pear"', "myself sees pear_1",
    )  # fmt: skip


@pytest.mark.parametrize(
    ("text", "kind"),
    [("what did i ask you for", "asked_for"), ("what did i ask you to do again", "asked_for"),
     ("what is left", "untracked"), ("what were you doing", "untracked")],
)  # fmt: skip
def test_the_questions_are_read_whole(text: str, kind: str) -> None:
    asked = recalled(english(), tuple(text.split()))
    assert asked is not None and asked.question == kind


@pytest.mark.parametrize("text", ["what is left of the cake", "what did i ask bo", "what is on the left"])
def test_other_questions_are_not_these(text: str) -> None:
    assert recalled(english(), tuple(text.split())) is None


def test_the_speakers_requests_are_said_back_in_order(kitchen_table: KB) -> None:
    history = [("user", "bring me the cup"), ("robot", "OK, I will bring the cup to you."),
               ("user", "where is the pear?"), ("robot", "I don't know where the pear is right now."),
               ("user", "give Bo the pear"), ("robot", "OK, I will bring the pear to Bo."),
               ("user", "oh and the cup too"), ("robot", "OK, I will bring the cup to Bo.")]  # fmt: skip
    out = say(kitchen_table, "what did I ask you for?", speaker=ANA, history=history)
    assert out.intent is None
    assert out.reply == ("You asked me to bring the cup to you, then bring the pear to Bo, "
                         "then bring the cup to Bo.")  # (questions are no requests)


def test_only_the_speakers_own_requests_are_theirs(kitchen_table: KB) -> None:
    out = say(kitchen_table, "what did I ask you for?", speaker="person_bo",
              history=[("user", "hello"), ("robot", "Hello!")])  # fmt: skip
    assert out.reply == "I don't remember you asking me for anything in this conversation."


def test_what_is_not_kept_is_said_plainly(kitchen_table: KB) -> None:
    history = [("user", "bring me the cup"), ("robot", "OK, I will bring the cup to you.")]
    out = say(kitchen_table, "what's left?", speaker=ANA, history=history)
    assert out.intent is None and out.understood and "don't keep track" in out.reply
    assert say(kitchen_table, "bring me the pear", speaker=ANA).intent == I.BRING_OBJECT  # (still a request)


def test_earlier_recall_questions_are_not_read_again(
    kitchen_table: KB, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Each recall question read again would recall the shorter history again: twice the work per
    # question asked before. The spy stops that at a budget a linear reading stays far under.
    reads = 0
    interpret = Interpreter.interpret

    def counted(self: Interpreter, text: str) -> Outcome:
        nonlocal reads
        reads += 1
        assert reads < 100, "earlier turns are read again and again"
        return interpret(self, text)

    monkeypatch.setattr(Interpreter, "interpret", counted)
    history = [("user", "bring me the cup"), ("robot", "OK, I will bring the cup to you.")]
    for _ in range(15):
        history += [("user", "what did I ask you for?"), ("robot", "You asked me to bring the cup to you.")]
    out = say(kitchen_table, "what did I ask you for?", speaker=ANA, history=history)
    assert out.reply == "You asked me to bring the cup to you."


def test_only_the_latest_user_turns_are_read_again(kitchen_table: KB) -> None:
    history = [("user", "give Bo the pear"), ("robot", "OK, I will bring the pear to Bo.")]
    history += [("user", "hello"), ("robot", "Hello!")] * MAX_READ
    out = say(kitchen_table, "what did I ask you for?", speaker=ANA, history=history)
    assert out.reply == "I don't remember you asking me for anything in this conversation."


def test_yes_to_a_request_proposed_back_is_that_request_once(kitchen_table: KB) -> None:
    history = [("user", "give Bo the pear"), ("robot", "Shall I bring the pear to Bo?"), ("user", "yes please"),
               ("robot", "OK, I will bring the pear to Bo.")]  # fmt: skip
    yes = say(kitchen_table, "yes please", speaker=ANA, history=history[:2])
    assert yes.roles == {"object": "pear_1", "recipient": "person_bo"}  # (the yes is that request again)
    out = say(kitchen_table, "what did I ask you for?", speaker=ANA, history=history)
    assert out.reply == "You asked me to bring the pear to Bo."
