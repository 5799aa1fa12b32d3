"""Social talk: each act that is neither a request nor a question, answered by its row of `TALK`."""

from dialogue import intents as I
from dialogue.understanding.interpret import ACTS, Interpreter
from dialogue.understanding.parsed import Parse
from dialogue.understanding.talk import TALK
from kb import KB
from tests.dialogue.conftest import lexicon_of

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
