"""The rules' grammar of statements: what a person tells, as facts with KB ids (or a kind's words)."""

from __future__ import annotations

import pytest

from dialogue.history import ASSISTANT_USER_ID, Utterance
from dialogue.understanding.statements.grammar import Statements
from kb import KB
from tests.dialogue.conftest import lexicon_of

BOB = "person_bob"


def facts(kb: KB, text: str, history: list[Utterance] | None = None) -> list[tuple[str | None, ...]] | None:
    told = Statements(lexicon_of(kb), BOB, history or []).read(text)
    if told is None:
        return None
    assert told.reply is None, told.reply
    return [(f.subject, f.predicate, f.object) for f in told.facts]


def refusal(kb: KB, text: str) -> str | None:
    told = Statements(lexicon_of(kb), BOB).read(text)
    assert told is not None and not told.facts
    return told.reply


@pytest.mark.parametrize(("text", "name"), [
    ("I'm Bob", "Bob"), ("my name is Bob", "Bob"), ("call me Bob", "Bob"), ("Call me Bob, please", "Bob"),
    ("im bob", "Bob"), ("I am Mary Jane", "Mary Jane"), ("you can call me bobby", "Bobby"),
    ("Well, my name's Bob.", "Bob"), ("I'm Frank", "Frank"),
    ("they call me Bobby", "Bobby"), ("my friends call me Bobby", "Bobby"), ("name's Bob", "Bob"),
    ("Bob is my name", "Bob"),
])
def test_a_speaker_tells_their_name(home: KB, text: str, name: str) -> None:
    assert facts(home, text) == [(BOB, "name", name)]


@pytest.mark.parametrize("text", ["I'm hungry", "I'm tired", "im back", "im frank with you", "I'm not sure",
                                  "I'm the cook", "I'm going home", "I am here",
                                  # a name said with "my name is" is still no negation or phrase
                                  "my name is not important", "my name is not Bob", "my name is a secret",
                                  # "call me" + when, how or what to call: a request, no name
                                  "call me a taxi", "call me later", "call me back", "call me maybe",
                                  "call me when you are done", "call me an ambulance",
                                  # participles and numbers in lower-case recogniser text
                                  "I'm lost", "im bored", "i'm scared", "I'm thirty", "i am twenty five"])
def test_what_is_no_name_is_not_taken_for_one(home: KB, text: str) -> None:
    assert facts(home, text) is None


def test_a_name_is_told_without_the_quotes_around_it(home: KB) -> None:
    assert facts(home, 'my name is "Bob" Smith') == [(BOB, "name", "Bob Smith")]
    assert facts(home, "call me 'Bobby'") == [(BOB, "name", "Bobby")]
    assert facts(home, "my name is " + "A" * 70) is None  # longer than any name


def test_a_greeting_with_a_name_is_both(home: KB) -> None:
    told = Statements(lexicon_of(home), BOB).read("Hi robot, I'm Bob!")
    assert told is not None and told.greeted
    assert [(f.subject, f.predicate, f.object) for f in told.facts] == [(BOB, "name", "Bob")]


def test_a_correction_renames_whom_the_robot_just_named(home: KB) -> None:
    home.update([f'{BOB} rdfs:label "Bob"'])
    history = [Utterance(BOB, "I'm Bob"), Utterance(ASSISTANT_USER_ID, "Nice to meet you, Bob.")]
    assert facts(home, "no, it's Rob", history) == [(BOB, "name", "Rob")]
    assert facts(home, "No, my name is Rob.", history) == [(BOB, "name", "Rob")]
    # Without the robot having named anyone, "no, it's Rob" is nothing this grammar reads.
    assert facts(home, "no, it's Rob") is None


def test_the_answer_to_the_robots_question_is_a_name(home: KB) -> None:
    asked = [Utterance(BOB, "what's my name?"),
             Utterance(ASSISTANT_USER_ID, "I don't know your name yet. What is it?")]
    assert facts(home, "Bob", asked) == [(BOB, "name", "Bob")]
    assert facts(home, "it's Bob", asked) == [(BOB, "name", "Bob")]
    assert facts(home, "Bob") is None


def test_this_is_names_the_one_person_present_without_a_name(home: KB) -> None:
    assert facts(home, "this is Maria") == [("person_x", "name", "Maria")]
    assert facts(home, "This is my friend Maria.") == [("person_x", "name", "Maria")]
    home.update(["person_y rdf:type Human", "myself sees person_y"])
    assert refusal(home, "this is Maria") == (
        "Sorry, I see more than one person I don't know: I can't tell who you mean.")
    home.remove(["myself sees person_y", "myself sees person_x"])
    assert refusal(home, "this is Maria") == "Sorry, I don't see anyone here whose name I don't know."


@pytest.mark.parametrize(("text", "expected"), [
    ("the red mug is mine", [("mug_red", "belongsTo", BOB)]),
    ("this is my mug", [("mug_red", "belongsTo", BOB)]),
    ("that phone belongs to Ines", [("phone_1", "belongsTo", "person_ines")]),
    ("the phone belongs to me", [("phone_1", "belongsTo", BOB)]),
    ("the cookbook is Alice's", [("book_1", "belongsTo", "person_alice")]),
    ("I own the remote", [("remote_1", "belongsTo", BOB)]),
    ("these are my keys", [("keys_1", "belongsTo", BOB)]),
    ("those are my glasses", [("glasses_1", "belongsTo", BOB)]),
])
def test_ownership(home: KB, text: str, expected: list[tuple[str, ...]]) -> None:
    assert facts(home, text) == expected


@pytest.mark.parametrize(("text", "expected"), [
    ("the keys are in the drawer", [("keys_1", "isIn", "drawer_1")]),
    ("the keys are now inside the drawer", [("keys_1", "isIn", "drawer_1")]),
    ("I've put the keys in the drawer", [("keys_1", "isIn", "drawer_1")]),
    ("I left my glasses on the sofa", [("glasses_1", "belongsTo", BOB), ("glasses_1", "isOn", "sofa_1")]),
    ("the glasses are on top of the table", [("glasses_1", "isOn", "table_1")]),
    ("I am in the kitchen", [(BOB, "isIn", "kitchen")]),
    ("I'm on the sofa", [(BOB, "isOn", "sofa_1")]),
])
def test_locations(home: KB, text: str, expected: list[tuple[str, ...]]) -> None:
    assert facts(home, text) == expected


def test_several_statements_in_one_turn(home: KB) -> None:
    assert facts(home, "I'm Bob and I like tea. The red mug is mine.") == [
        (BOB, "name", "Bob"), (BOB, "likes", "tea"), ("mug_red", "belongsTo", BOB)]


@pytest.mark.parametrize("text", [
    "tell alice her tea is on the table",  # a request: what to tell her is no statement of the speaker's
    "bring me the mug", "is the mug on the table?", "I'd like a cup of tea", "where are my keys",
    "the moon is made of cheese", "does Alice like tea", "what do you see", "I'm Bob, bring me the mug",
    "i hate marking lab reports",
    # where the speaker is, said of no place the KB knows: idioms, left to the other rules
    "I'm on my way", "I'm in a hurry", "I'm in trouble", "I'm on the phone", "I'm on it", "I'm in love",
    "I'm in the drawer",
    # a noun phrase with its relative clause, an object question: no subject of a statement
    "the one that's mine", "describe what's on the table",
])
def test_what_is_not_a_statement_is_left_to_the_other_rules(home: KB, text: str) -> None:
    assert facts(home, text) is None


def test_nothing_is_invented_and_ambiguity_is_asked_about(home: KB) -> None:
    assert refusal(home, "the umbrella is mine") == "Sorry, I don't know any umbrella."
    assert refusal(home, "the mug belongs to Zoe") == "Sorry, I don't know anyone called Zoe."
    home.update(["mug_blue rdf:type dbr:Cup", 'mug_blue rdfs:label "mug"', "mug_blue hasColor blue",
                 "myself sees mug_blue"])
    told = Statements(lexicon_of(home), BOB).read("the mug is mine")
    assert told is not None and told.clarify and told.reply is not None and "red" in told.reply


def test_a_statement_run_into_a_request_is_no_statement(home: KB) -> None:
    # "...can you get them" is a request: the turn is the rules' (which may not know the glasses),
    # not a refusal to learn where unknown glasses are.
    assert Statements(lexicon_of(home), BOB).read("my sunglasses are on the table can you get them") is None


def test_a_greeting_run_into_the_clause_is_taken_off_it(home: KB) -> None:
    # "hiya whats on the table" asks (it was read as "hiya what" being on the table)
    assert Statements(lexicon_of(home), BOB).read("hiya whats on the table") is None
    told = Statements(lexicon_of(home), BOB).read("hiya the keys are in the drawer")
    assert told is not None and told.greeted
    assert [(f.subject, f.predicate, f.object) for f in told.facts] == [("keys_1", "isIn", "drawer_1")]


@pytest.mark.parametrize(("text", "expected"), [
    ("no, they're in the drawer", [("keys_1", "isIn", "drawer_1")]),
    ("nope, they are on the sofa now", [("keys_1", "isOn", "sofa_1")]),
    ("actually the keys are in the drawer now", [("keys_1", "isIn", "drawer_1")]),
])  # fmt: skip
def test_a_correction_of_the_robots_answer_is_told_of_the_thing_it_named(
    home: KB, text: str, expected: list[tuple[str, ...]]
) -> None:
    history = [Utterance(BOB, "where are my keys?"), Utterance(ASSISTANT_USER_ID, "The keys are in the kitchen.")]
    assert facts(home, text, history) == expected


def test_they_with_nothing_spoken_of_is_asked_about(home: KB) -> None:
    told = Statements(lexicon_of(home), BOB).read("no, they're in the drawer")
    assert told is not None and not told.facts and told.clarify


@pytest.mark.parametrize(("text", "expected"), [
    ("I'm Bob, Alice's brother", [(BOB, "name", "Bob")]),
    ("I'm Bob, I'm the father of Ines", [(BOB, "name", "Bob")]),
    ("this is my colleague Maria, she's visiting", [("person_x", "name", "Maria")]),
    ("this is Maria, my sister", [("person_x", "name", "Maria")]),
])  # fmt: skip
def test_an_introduction_may_say_more_than_the_name(home: KB, text: str, expected: list[tuple[str, ...]]) -> None:
    assert facts(home, text) == expected


@pytest.mark.parametrize("text", [
    # said of someone without an introduction, or not who they are to someone: left to the other rules
    "Alice's brother", "she's visiting", "I'm Bob, bring me the mug", "this is Maria, she's not Ines",
    "I'm Bob, I'm hungry",
])  # fmt: skip
def test_what_an_introduction_does_not_say_is_not_taken_for_it(home: KB, text: str) -> None:
    assert facts(home, text) is None
