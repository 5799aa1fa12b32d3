"""Pronouns and their antecedents: "her" and "him" are people, "it" a thing; the request's own words,
what a self-repair took back and whose thing a turn said it was all count as context."""

import pytest

from dialogue import intents as I
from dialogue.history import ASSISTANT_USER_ID, Utterance
from dialogue.understanding.interpret import Interpreter
from dialogue.understanding.outcome import Outcome
from kb import KB
from tests.dialogue.conftest import lexicon_of, scene_kb

SPEAKER = "person_kim"


@pytest.fixture
def cloakroom() -> KB:
    return scene_kb(
        None,
        f"{SPEAKER} rdf:type Human", f'{SPEAKER} rdfs:label "Kim"', f"myself sees {SPEAKER}",
        "person_ravi rdf:type Human", 'person_ravi rdfs:label "Ravi"', "myself sees person_ravi",
        "person_mia rdf:type Human", 'person_mia rdfs:label "Mia"', "myself sees person_mia",
        "hook_1 rdf:type Artifact", 'hook_1 rdfs:label "coat hook"', "myself sees hook_1",
        "shelf_1 rdf:type Artifact", 'shelf_1 rdfs:label "hat shelf"', "myself sees shelf_1",
        "scarf_r rdf:type Artifact", 'scarf_r rdfs:label "scarf"', "scarf_r belongsTo person_ravi",
        "scarf_r isOn hook_1", "myself sees scarf_r",
        "scarf_k rdf:type Artifact", 'scarf_k rdfs:label "scarf"', f"scarf_k belongsTo {SPEAKER}",
        "scarf_k isOn shelf_1", "myself sees scarf_k",
        "stapler_1 rdf:type Artifact", 'stapler_1 rdfs:label "stapler"', "myself sees stapler_1",
    )  # fmt: skip


def say(kb: KB, text: str, *history: tuple[str, str]) -> Outcome:
    turns = [Utterance(SPEAKER if who == "user" else ASSISTANT_USER_ID, t) for who, t in history]
    return Interpreter(lexicon_of(kb), SPEAKER, turns).interpret(text)


def test_her_and_him_are_people_and_it_a_thing(cloakroom: KB) -> None:
    # The robot's last words name Ravi's scarf and Ravi: "it" is the scarf, "him" is Ravi, never the
    # scarf ("bring the scarf to the scarf").
    out = say(cloakroom, "could you take it to him", ("user", "wheres ravis scarf"),
              ("robot", "Ravi's scarf is on the coat hook."))  # fmt: skip
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "scarf_r", "recipient": "person_ravi"})


def test_a_person_named_in_the_request_is_who_him_or_her_means(cloakroom: KB) -> None:
    out = say(cloakroom, "take ravi's stapler to him")
    assert out.roles == {"object": "stapler_1", "recipient": "person_ravi"}, out.reply
    out = say(cloakroom, "mia can't find the stapler, can you take it to her")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "stapler_1", "recipient": "person_mia"})


def test_them_taken_to_a_person_is_carried_not_guided(cloakroom: KB) -> None:
    # "them" is the things just spoken of; taken to a person, they are brought to her.
    out = say(cloakroom, "take them to mia", ("user", "where are the staplers"),
              ("robot", "The stapler is here."))  # fmt: skip
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "stapler_1", "recipient": "person_mia"})


def test_whose_thing_a_turn_said_it_was_picks_the_antecedent(cloakroom: KB) -> None:
    # Two scarves: "your scarf" in the robot's words is the speaker's, "my scarf" in hers too.
    out = say(cloakroom, "great bring it here", ("user", "can you see my scarf"),
              ("robot", "Yes, your scarf is on the hat shelf."))  # fmt: skip
    assert out.roles == {"object": "scarf_k", "recipient": SPEAKER}, out.reply
    out = say(cloakroom, "bring it here", ("user", "ravis scarf is somewhere"), ("robot", "OK."))
    assert out.roles == {"object": "scarf_r", "recipient": SPEAKER}, out.reply
    # Where the same turn puts the thing tells it apart too.
    out = say(cloakroom, "fetch it", ("robot", "A scarf is on the coat hook."))
    assert out.roles == {"object": "scarf_r", "recipient": SPEAKER}, out.reply


def test_what_a_self_repair_took_back_is_context_for_the_new_request(cloakroom: KB) -> None:
    out = say(cloakroom, "hand ravi the uh no wait hand him the stapler")
    assert out.roles == {"object": "stapler_1", "recipient": "person_ravi"}, out.reply


def test_him_before_a_noun_phrase_is_a_recipient_even_when_nobody_was_named(cloakroom: KB) -> None:
    # "give him the stapler" with no one spoken of: ask who, never give it to the speaker.
    out = say(cloakroom, "give him the stapler")
    assert out.clarify and out.intent is None and '"him"' in out.reply


def test_a_word_of_address_is_nobody_the_rules_can_name() -> None:
    # "take my calculator to sir": the teacher, whom the KB knows by name; never a grab without him
    kb = scene_kb(
        None, "p_o rdf:type Human", 'p_o rdfs:label "Mr Okafor"', "c_1 rdf:type Artifact",
        'c_1 rdfs:label "calculator"', "myself sees c_1", f"{SPEAKER} rdf:type Human",
    )  # fmt: skip
    out = Interpreter(lexicon_of(kb), SPEAKER).interpret("can you take my calculator to sir he wants to check it")
    assert out.intent is None and not out.understood
    kb.close()


def test_a_title_with_a_preposition_names_its_thing_whatever_is_said_around_it() -> None:
    kb = scene_kb(
        None, "b_1 rdf:type dbr:Book", 'b_1 rdfs:label "Murder on the Orient Express"', "myself sees b_1",
        "s_1 rdf:type Artifact", 's_1 rdfs:label "reservations shelf"', "b_1 isOn s_1", "b_2 rdf:type dbr:Book",
        'b_2 rdfs:label "The Gruffalo"', "myself sees b_2", f"{SPEAKER} rdf:type Human",
    )  # fmt: skip
    said = Interpreter(lexicon_of(kb), SPEAKER)
    out = said.interpret("could you get me my reserved book murder on the orient express its on the reservations shelf")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "b_1", "recipient": SPEAKER})
    # a title inside a modifier says where, not what
    assert said.interpret("get me the red box next to murder on the orient express").intent is None
    kb.close()


@pytest.mark.parametrize("text", ["give daddy my pear", "bring granny the pear", "bring granny her pear"])
def test_whom_a_thing_is_given_to_is_never_the_speaker_by_default(text: str) -> None:
    kb = scene_kb("office")
    out = Interpreter(lexicon_of(kb), "person_bob", ()).interpret(text)
    # (the KB says nothing of Bob's family: who is asked)
    assert out.intent is None and out.clarify and f"your {text.split()[1]}" in out.reply


def test_a_thing_given_with_no_one_said_is_for_the_speaker() -> None:
    kb = scene_kb("office")
    out = Interpreter(lexicon_of(kb), "person_bob", ()).interpret("pass the pear")
    assert out.roles == {"object": "pear_1", "recipient": "person_bob"}


def test_a_name_the_grammar_cut_at_a_preposition_is_the_thing_called_so() -> None:
    kb = scene_kb(
        None,
        f"{SPEAKER} rdf:type Human", f'{SPEAKER} rdfs:label "Kim"', f"myself sees {SPEAKER}",
        "person_ravi rdf:type Human", 'person_ravi rdfs:label "Ravi"', "myself sees person_ravi",
        "card_1 rdf:type Artifact", 'card_1 rdfs:label "key card for room 12"', "myself sees card_1",
        "card_2 rdf:type Artifact", 'card_2 rdfs:label "key card for room 40"', "myself sees card_2",
    )  # fmt: skip
    out = Interpreter(lexicon_of(kb), SPEAKER).interpret("take the key card for room 40 to Ravi")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "card_2", "recipient": "person_ravi"})
    assert out.reply == "OK, I will bring the key card for room 40 to Ravi."
    # a phrase that only starts a name is still the grammar's ("for room" is whom for)
    assert Interpreter(lexicon_of(kb), SPEAKER).interpret("take the key card for Ravi").clarify


def test_her_before_a_noun_after_a_name_is_the_named_persons_thing() -> None:
    kb = scene_kb("office")
    out = Interpreter(lexicon_of(kb), "person_bob", ()).interpret("bring Carol her pear")
    assert out.roles == {"object": "pear_1", "recipient": "person_carol"}
    kb.close()


@pytest.fixture
def farm() -> KB:
    return scene_kb(
        None, "myself rdf:type Robot",
        f"{SPEAKER} rdf:type Human", f'{SPEAKER} rdfs:label "Kim"', f"myself sees {SPEAKER}",
        "shed rdf:type ZoneOfInterest", 'shed rdfs:label "tool shed"',
        "lifts rdf:type ZoneOfInterest", 'lifts rdfs:label "lifts"',
    )  # fmt: skip


@pytest.mark.parametrize(
    ("text", "intent", "mentions"),
    [("bring me the tool", None, "tool"), ("I need the lifts", I.GUIDE, "lifts"), ("bring me the shed", I.GUIDE, "shed")],
)
def test_a_place_is_named_by_its_head_not_by_a_word_its_name_holds(
    farm: KB, text: str, intent: str | None, mentions: str
) -> None:
    out = Interpreter(lexicon_of(farm), SPEAKER).interpret(text)
    assert out.intent == intent and mentions in out.reply
