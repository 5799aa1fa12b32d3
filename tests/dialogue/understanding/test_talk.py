"""Social talk: each act that is neither a request nor a question, answered by its row of `TALK`."""

import pytest

from dialogue import intents as I
from dialogue.understanding.interpret import ACTS, Interpreter
from dialogue.understanding.parsed import Parse
from dialogue.understanding.talk import TALK
from kb import KB
from tests.dialogue.conftest import lexicon_of
from tests.dialogue.understanding.test_interpret import say

BOB = "person_bob"


def test_each_act_of_talk_is_answered_and_only_a_greeting_acts(office: KB) -> None:
    reader = Interpreter(lexicon_of(office), BOB)
    out = {act: answer(reader, Parse(act), {}) for act, answer in TALK.items()}
    assert (out["greeting"].intent, out["greeting"].roles) == (I.GREET, {"recipient": BOB})
    assert all(o.intent is None for act, o in out.items() if act != "greeting")
    assert out["farewell"].farewell and not out["thanks"].farewell
    assert all(o.reply for o in out.values())


def test_the_interpreter_reads_every_act_of_talk() -> None:
    assert set(TALK) <= set(ACTS)


def test_the_interpreter_reads_talk_by_its_table(office: KB) -> None:
    reader = Interpreter(lexicon_of(office), BOB)
    assert reader.interpret("thanks a lot").reply == TALK["thanks"](reader, Parse("thanks"), {}).reply
    everyone = TALK["greeting"](reader, Parse("greeting", slots={"everyone": ("everyone",)}), {})
    assert everyone.intent is None and everyone.reply == "Hello everyone!"


def test_never_mind_just_after_the_robot_took_on_a_request_stops_it(office: KB) -> None:
    acting = [("user", "bring me the pear"), ("assistant", "OK, I will bring the pear to you.")]
    out = say(office, "Actually, never mind.", history=acting)
    assert (out.intent, out.roles) == (I.STOP_ACTIVITY, {})
    # after a question, or with no request taken on, there is nothing to stop
    for history in ([("user", "bring me the mug"), ("assistant", "Which mug do you mean?")],
                    [("user", "hello"), ("assistant", "Hello Bob!")], []):
        out = say(office, "never mind", history=history)
        assert (out.intent, out.reply) == (None, "OK, I won't do that.")


@pytest.mark.parametrize(
    "text", ["When Carol gets here, give her the pear.", "when carol's back, bring her the pear", "if Carol comes by, give her the pear",
             "once Carol arrives, give her the pear", "When Carol turns up, give her the pear"]
)
def test_a_condition_that_waits_for_someone_names_them(office: KB, text: str) -> None:
    out = say(office, text)
    assert out.intent is None and out.reply == "I can't wait for Carol myself: tell me again when Carol is here."


@pytest.mark.parametrize(
    "text", ["when the bell rings, give Carol the pear", "when Carol leaves, bring the pear to Dan",
             "after Carol has gone home, bring me the pear"]
)
def test_a_condition_that_waits_for_no_one_known_says_it_waits(office: KB, text: str) -> None:
    # (Carol leaving is no one to wait for: the robot would be told to wait for her to be here)
    out = say(office, text)
    assert out.intent is None and out.reply == "I can't wait for that myself: tell me again when it happens."
