import pytest

from dialogue import intents as I
from dialogue.reference.grounding import build_snapshot
from dialogue.reference.lexicon import Lexicon
from dialogue.schema import AnswerError, ChatbotResponse, UserIntent
from dialogue.validate import ground_answer
from kb import KB
from tests.dialogue.conftest import english


def answer(**intent: str | None) -> ChatbotResponse:
    return ChatbotResponse(verbal_ack="ok", user_intent=UserIntent.model_validate(intent))


def test_ids_names_and_me_are_grounded(kitchen: KB) -> None:
    lex = Lexicon(build_snapshot(kitchen), english())
    got = ground_answer(answer(type=I.BRING_OBJECT, object="the cookbook", recipient="me"), lex, "person_alice")
    assert got.intents[0].data == {"object": "book_1", "recipient": "person_alice"}
    assert got.intents[0].confidence == 0.7 and got.intents[0].source == "person_alice"


def test_wrong_kind_is_refused_with_the_allowed_ids(kitchen: KB) -> None:
    lex = Lexicon(build_snapshot(kitchen), english())
    with pytest.raises(AnswerError, match=r"object 'person_tom' is not the id of a thing.*cup_1"):
        ground_answer(answer(type=I.GRAB_OBJECT, object="person_tom"), lex, "person_alice")


def test_free_form_values_and_dropped_roles(kitchen: KB) -> None:
    lex = Lexicon(build_snapshot(kitchen), english())
    got = ground_answer(answer(type=I.START_ACTIVITY, object="clean_table", goal="kitchen"), lex, "p")
    assert got.intents[0].data == {"object": "clean_table"}
    with pytest.raises(AnswerError, match="missing required role"):
        ground_answer(answer(type=I.SAY, recipient="person_tom"), lex, "p")


def test_no_intent_needs_a_reply(kitchen: KB) -> None:
    lex = Lexicon(build_snapshot(kitchen), english())
    assert ground_answer(ChatbotResponse(verbal_ack="It is noon."), lex, "p").intents == ()
    with pytest.raises(AnswerError, match="both verbal_ack and user_intent are null"):
        ground_answer(ChatbotResponse(), lex, "p")


def test_an_ordered_list_of_intents_is_grounded_in_order(kitchen: KB) -> None:
    lex = Lexicon(build_snapshot(kitchen), english())
    first = UserIntent(type=I.MOVE_TO, goal="table_1")
    second = UserIntent(type=I.BRING_OBJECT, object="the cookbook", recipient="me")
    got = ground_answer(ChatbotResponse(verbal_ack="ok", user_intent=first, user_intents=[first, second]), lex, "person_alice")
    assert [(i.intent, i.data) for i in got.intents] == [
        (I.MOVE_TO, {"goal": "table_1"}),
        (I.BRING_OBJECT, {"object": "book_1", "recipient": "person_alice"}),
    ]


def test_a_bad_intent_anywhere_in_the_list_refuses_the_whole_answer(kitchen: KB) -> None:
    lex = Lexicon(build_snapshot(kitchen), english())
    good = UserIntent(type=I.MOVE_TO, goal="table_1")
    with pytest.raises(AnswerError, match="not one of"):
        ground_answer(ChatbotResponse(user_intents=[good, UserIntent(type="dance")]), lex, "p")
    with pytest.raises(AnswerError, match="not the id"):
        ground_answer(ChatbotResponse(user_intents=[good, UserIntent(type=I.GRAB_OBJECT, object="piano")]), lex, "p")


def test_the_allowed_ids_are_the_first_of_the_situation_not_the_whole_world() -> None:
    """In a large world the refusal names the first ids of the situation's order (what the robot
    sees, then people and places), at most 30, whatever else the KB holds."""
    kb = KB()
    kb.update(["myself rdf:type Robot", "person_ann rdf:type Human", "kitchen rdf:type ZoneOfInterest",
               *(f"box_{i:03} isIn kitchen" for i in range(200)), *(f"box_{i:03} rdf:type dbr:Box" for i in range(200)),
               "myself sees box_150", "myself sees box_199"])
    lex = Lexicon(build_snapshot(kb), english())
    with pytest.raises(AnswerError) as refused:
        ground_answer(answer(type=I.GRAB_OBJECT, object="person_ann"), lex, "person_ann")
    listed = str(refused.value).split("use one of ")[1].split("]")[0]
    ids = [part.strip(" '[") for part in listed.split(",")]
    assert len(ids) == 30 and {"box_150", "box_199"} <= set(ids) and ids == sorted(ids)
    with pytest.raises(AnswerError, match=r"not the id of a person.*\['person_ann'\]"):
        ground_answer(answer(type=I.GREET, recipient="box_001"), lex, "person_ann")
