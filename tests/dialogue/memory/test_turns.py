"""Knowledge from dialogue end to end through the engine: the rules, and a scripted model's `facts`."""

from __future__ import annotations

import asyncio
from typing import Any

import pytest

from dialogue.engine import DialogueEngine, TurnResult
from dialogue.history import ASSISTANT_USER_ID, Utterance
from dialogue.llm.hybrid import HybridModel
from dialogue.llm.testing import ScriptedModel
from dialogue.memory.learn import Memory, Trust
from dialogue.memory.provenance import told
from kb import KB, KbError

BOB = "person_bob"


class Talk:
    """One person's side of a conversation with an engine, history kept."""

    def __init__(self, engine: DialogueEngine, speaker: str = BOB) -> None:
        self.engine = engine
        self.speaker = speaker
        self.history: list[Utterance] = []

    def say(self, text: str) -> TurnResult:
        result = asyncio.run(self.engine.turn(text, speaker=self.speaker, history=self.history))
        self.history += [Utterance(self.speaker, text), Utterance(ASSISTANT_USER_ID, result.response)]
        return result


def test_names_with_the_rules(home: KB) -> None:
    bob = Talk(DialogueEngine(home))
    assert bob.say("Hi, I'm Bob").response == "Hello! Nice to meet you, Bob."
    assert [i.intent for i in bob.history and bob.say("what's my name?").intents] == []
    assert bob.history[-1].text == "Your name is Bob."
    assert bob.say("no, it's Rob").response == "Got it: Rob, not Bob."
    assert [r["l"] for r in home.find(f"{BOB} rdfs:label ?l")] == ["Rob"]
    assert bob.say("who am I?").response == "Your name is Rob."
    assert bob.say("this is Maria").response == "Nice to meet you, Maria."
    assert bob.say("who do you see?").response == "I see Alice and Maria."


def test_a_refused_statement_is_not_learnt_at_all_and_the_reply_says_so(home: KB) -> None:
    def refuse(commit: object) -> None:
        # The disk fills once the speaker's belief would be written: refused, it must not stay.
        if any(d.model == "default" for d in commit.deltas):  # type: ignore[attr-defined]
            raise KbError("no space left on device")

    unregister = home.on_commit(refuse, durable=True)  # the journal on a full disk
    result = Talk(DialogueEngine(home)).say("Hi, I'm Bob")
    assert result.response == "Sorry, I could not remember that."
    assert "no space left on device" in result.error_msg
    assert home.models() == ["default"] and home.find(f"{BOB} rdfs:label ?l") == []  # no belief left behind
    unregister()
    assert Talk(DialogueEngine(home)).say("Hi, I'm Bob").response == "Hello! Nice to meet you, Bob."
    assert home.find(f"{BOB} rdfs:label ?l", models=[BOB]) == [{"l": "Bob"}]


def test_ownership_and_places_are_used_by_later_questions(home: KB) -> None:
    bob = Talk(DialogueEngine(home))
    assert bob.say("the red mug is mine").response == "OK, the mug is yours."
    assert bob.say("whose mug is this?").response == "The mug is yours."
    assert bob.say("I left my keys in the drawer").response == "OK, the keys are yours and the keys are in the drawer."
    assert bob.say("where are my keys?").response.startswith("The keys are in the drawer")
    # Perception wins, and the robot says so: it sees the remote on the sofa.
    assert bob.say("I own the remote. The remote is in the drawer.").response == (
        "OK, the remote is yours. I can see the remote on the couch, though.")
    assert home.is_asserted("remote_1 isOn sofa_1") and not home.is_asserted("remote_1 isIn drawer_1")


def test_preferences_under_each_trust_policy(home: KB) -> None:
    bob = Talk(DialogueEngine(home))  # the default policy: what people say of themselves
    assert bob.say("I'm Bob and I like tea").response == "Nice to meet you, Bob. OK, you like tea."
    assert bob.say("Alice hates coffee").response == "OK, I'll remember that you said Alice doesn't like coffee."
    assert bob.say("what does Alice hate?").response == "You told me Alice doesn't like coffee."
    alice = Talk(bob.engine, "person_alice")
    assert alice.say("what does Alice hate?").response == "Bob told me you don't like coffee."
    trusting = Talk(DialogueEngine(home, memory=Memory(home, Trust.ALL)))
    assert trusting.say("Alice likes chocolate").response == "Sorry, I don't know what chocolate is."
    assert trusting.say("Alice likes tea").response == "OK, Alice likes tea."
    assert Talk(bob.engine, "person_ines").say("what does Alice like?").response == "Alice likes tea."
    assert alice.say("what do I like?").response == "You like tea."


def test_a_model_tells_facts_in_its_answer_and_a_bad_id_is_repaired(home: KB) -> None:
    model = ScriptedModel([
        {"verbal_ack": "Sure!", "user_intent": None,
         "facts": [{"subject": "me", "predicate": "name", "object": "Bob"},
                   {"subject": "umbrella_9", "predicate": "belongsTo", "object": "me"}]},
        {"verbal_ack": "Sure!", "user_intent": None,
         "facts": [{"subject": "me", "predicate": "name", "object": "Bob"},
                   {"subject": "mug_red", "predicate": "belongsTo", "object": "me"}]},
    ])
    bob = Talk(DialogueEngine(home, model))
    result = bob.say("Bob here, and that red thing is my mug")
    assert result.response == "Nice to meet you, Bob. OK, the mug is yours." and result.backend == "scripted"
    assert "umbrella_9" in model.requests[1].messages[-1].content  # the repair said what was wrong
    assert home.is_asserted(f"mug_red belongsTo {BOB}") and home.is_asserted(f'{BOB} rdfs:label "Bob"')
    assert {t.predicate for t in told(home, by=BOB)} == {"rdfs:label", "belongsTo"}


def test_a_model_answer_with_an_intent_and_a_fact_says_both(home: KB) -> None:
    answer: dict[str, Any] = {
        "verbal_ack": "I will bring you the mug.",
        "user_intent": {"type": "__intent_bring_object__", "object": "mug_red", "recipient": BOB, "goal": None,
                        "input": None},
        "facts": [{"subject": "mug_red", "predicate": "belongsTo", "object": BOB}]}
    result = Talk(DialogueEngine(home, ScriptedModel([answer]))).say("bring me my mug, the red one is mine")
    assert result.response == "I will bring you the mug. OK, the mug is yours."
    assert [(i.intent, i.data) for i in result.intents] == [
        ("__intent_bring_object__", {"object": "mug_red", "recipient": BOB})]


def test_a_model_asks_about_what_was_told(home: KB) -> None:
    home.update(["person_alice likes dbr:Tea"])
    model = ScriptedModel([{"verbal_ack": None, "user_intent": None,
                            "facts": [{"subject": "person_alice", "predicate": "likes", "object": None}]}])
    assert Talk(DialogueEngine(home, model)).say("any idea what Alice fancies?").response == "Alice likes tea."


def test_the_hybrid_model_learns_with_its_rules_first(home: KB) -> None:
    model = ScriptedModel([])
    bob = Talk(DialogueEngine(home, HybridModel(model)))
    assert bob.say("my name is Bob").response == "Nice to meet you, Bob." and model.requests == []


def test_a_speaker_who_is_nobody_of_the_kb_is_told_so_and_nothing_is_learnt(home: KB) -> None:
    before = home.models()
    anonymous = Talk(DialogueEngine(home), "__unknown_agent__")
    for text in ("I'm Bob", "the phone belongs to Ines", "what's my name?"):
        assert anonymous.say(text).response == "Sorry, I don't know who you are."
    assert home.models() == before and told(home) == []
    assert anonymous.say("what does Alice like?").response == "I don't know what Alice likes."


def test_an_ambiguous_statement_is_asked_about_and_the_answer_completes_it(home: KB) -> None:
    home.update(["mug_blue rdf:type dbr:Cup", 'mug_blue rdfs:label "mug"', "mug_blue hasColor blue",
                 "mug_blue isOn table_1", "myself sees mug_blue"])
    bob = Talk(DialogueEngine(home))
    question = bob.say("the mug is mine")
    assert question.clarify and question.response.endswith("?") and question.claims == ()
    assert bob.say("the red one").response == "OK, the red mug is yours."
    assert home.is_asserted(f"mug_red belongsTo {BOB}") and not home.is_asserted(f"mug_blue belongsTo {BOB}")
    # A command's clarification is still the command grammar's.
    assert bob.say("bring me the mug").clarify
    assert [i.data for i in bob.say("the blue one").intents] == [{"object": "mug_blue", "recipient": BOB}]


def test_a_liking_of_the_robot_is_of_the_robot_and_said_so(home: KB) -> None:
    bob = Talk(DialogueEngine(home))
    assert bob.say("I like you").response == "OK, you like me."
    assert home.is_asserted(f"{BOB} likes myself") and not home.is_asserted(f"{BOB} likes {BOB}")
    assert bob.say("what do I like?").response == "You like me."


def test_the_robot_speaking_as_itself_teaches_itself_nothing(home: KB) -> None:
    robot = Talk(DialogueEngine(home), "myself")
    for text in ("I'm Bob", "I like tea"):
        assert robot.say(text).response == "Sorry, I don't know who you are."
    assert not home.is_asserted('myself rdfs:label "Bob"') and told(home) == []


def test_a_kind_is_said_back_as_it_was_told_in_the_plural_too(home: KB) -> None:
    bob = Talk(DialogueEngine(home))
    assert bob.say("I like apples").response == "OK, you like apples."
    assert bob.say("I like cats").response == "Sorry, I don't know what cats are."
    assert bob.say("I like jazz").response == "Sorry, I don't know what jazz is."


def test_the_name_of_someone_just_introduced_is_asked_about(home: KB) -> None:
    bob = Talk(DialogueEngine(home))
    assert bob.say("this is Maria").response == "Nice to meet you, Maria."
    assert bob.say("what is her name?").response == "That's Maria."
    assert bob.say("what is Alice's name?").response == "That's Alice."


ALICE, INES = "person_alice", "person_ines"


@pytest.mark.parametrize("trust", [Trust.PEOPLE, Trust.ALL])
def test_a_thing_told_to_be_someone_elses_stays_theirs_when_another_claims_it(home: KB, trust: Trust) -> None:
    """Issue 26: one person's word once took another's thing: Bob's "that mug is mine" after Alice's
    made it Bob's, and Alice's "bring me my mug" found no mug of hers."""
    engine = DialogueEngine(home, memory=Memory(home, trust))
    alice, bob, ines = Talk(engine, ALICE), Talk(engine, BOB), Talk(engine, INES)
    assert bob.say("I'm Bob").response == "Nice to meet you, Bob."
    assert alice.say("the red mug is mine").response == "OK, the mug is yours."
    assert bob.say("that mug is mine").response == "Alice told me the mug is theirs."
    assert home.is_asserted(f"mug_red belongsTo {ALICE}") and not home.is_asserted(f"mug_red belongsTo {BOB}")
    assert home.is_asserted(f"mug_red belongsTo {BOB}", BOB)  # Bob's belief, in his own model
    assert ines.say("the mug belongs to Bob").response == (
        "Alice told me the mug is theirs." if trust is Trust.ALL
        else "OK, I'll remember that you said the mug is Bob's.")
    assert bob.say("I left my mug on the sofa").response == (  # not his: where it is stays his belief
        "I can see the mug on the table, though." if trust is Trust.ALL
        else "OK, I'll remember that you said the mug is on the couch.")
    assert home.is_asserted("mug_red isOn table_1") and not home.is_asserted("mug_red isOn sofa_1")
    # What others ask for still means Alice's mug, and so does what Alice asks for.
    (fetch,) = alice.say("bring me my mug").intents
    assert (fetch.intent, fetch.data) == ("__intent_bring_object__", {"object": "mug_red", "recipient": ALICE})
    assert ines.say("whose mug is this?").response == "The mug is Alice's."
    assert [t.by for t in told(home, subject="mug_red")] == [ALICE]
    # Alice may still give it away herself.
    if trust is Trust.ALL:
        assert alice.say("the mug belongs to Ines").response == "OK, the mug is Ines's."
        assert home.is_asserted(f"mug_red belongsTo {INES}")


def test_the_name_of_another_known_person_stays_the_speakers_belief(home: KB) -> None:
    """Issue 26: Bob's "I'm Alice", Alice being known, once named Bob Alice in the robot's model, and
    "bring the mug to Alice" could go to him."""
    engine = DialogueEngine(home)
    alice, bob, ines = Talk(engine, ALICE), Talk(engine, BOB), Talk(engine, INES)
    assert bob.say("I'm Alice").response == "I know someone else called Alice."
    assert bob.say("hi, my name is alice").response == "Hello! I know someone else called Alice."
    assert home.find(f"{BOB} rdfs:label ?l") == [] and home.find(f"{BOB} rdfs:label ?l", models=[BOB]) == [
        {"l": "Alice"}]
    for speaker in (ines, bob):
        (bring,) = speaker.say("bring the mug to Alice").intents
        assert bring.data == {"object": "mug_red", "recipient": ALICE}, speaker.speaker
    assert ines.say("who do you see?").response == "I see Alice and someone I don't know."
    assert alice.say("I'm Alice").response == "I know, Alice."  # her own name, of course
    assert bob.say("I'm Bob").response == "Nice to meet you, Bob."
