"""Ask dialogues through the dialogue manager: the rules, a scripted model, a hybrid, stateless turns,
another language, and each turn's trace."""

from __future__ import annotations

import asyncio
import json
from dataclasses import replace

from dialogue.ask.form import ASK_ROLE
from dialogue.engine import DialogueEngine, EngineConfig, TurnResult
from dialogue.history import ASSISTANT_USER_ID, SYSTEM_USER_ID, Utterance
from dialogue.intents import RAW_USER_INPUT
from dialogue.llm.hybrid import HybridModel
from dialogue.llm.testing import ScriptedModel
from dialogue.sessions.manager import DialogueManager
from kb import KB
from tests.dialogue.ask.conftest import NINA, PROPERTIES

CONFIG = json.dumps({"question": "How old are you, and which cup?",
                     "result_schema_properties": {"age": PROPERTIES["age"], "cup": PROPERTIES["cup"]}})


def answer(answers: dict[str, object], ack: str | None = None, cancel: bool = False) -> dict[str, object]:
    return {"answers": answers, "cancel": cancel, "verbal_ack": ack}


def talk(manager: DialogueManager, dialogue_id: str, *texts: str, locale: str | None = None) -> list[TurnResult]:
    async def run() -> list[TurnResult]:
        return [await manager.interact(NINA, t, dialogue_id=dialogue_id, locale=locale) for t in texts]

    return asyncio.run(run())


def test_rules_fill_the_form_with_a_clarification_and_a_correction(cups: KB) -> None:
    manager = DialogueManager(DialogueEngine(cups))
    started = manager.start(ASK_ROLE, configuration=CONFIG)
    assert manager.opening_line(started) == "How old are you, and which cup?"
    first, second, third = talk(manager, started.id, "I'm thirty-three and the cup", "the red one", "no, I'm 34")
    assert first.response == "Which cup do you mean: the blue cup or the red cup?" and first.clarify
    assert (first.dialogue_terminal, json.loads(first.results or "")) == (False, {"age": 33})
    assert second.dialogue_terminal and json.loads(second.results or "") == {"age": 33, "cup": "cup_red"}
    assert second.response == "Thank you." and second.intents == ()
    # The form is over: a later answer changes nothing and says so.
    assert third.dialogue_terminal and json.loads(third.results or "") == {"age": 33, "cup": "cup_red"}
    assert "over" in third.error_msg and third.trace is not None and third.trace.answered_by == "form"
    history = [(u.speaker, u.text) for u in manager.get(started.id).history]
    assert history[:3] == [(ASSISTANT_USER_ID, "How old are you, and which cup?"), (NINA, "I'm thirty-three and the cup"),
                           (ASSISTANT_USER_ID, first.response)]


def test_one_answer_with_a_yes_said_inside_it_fills_both_fields(cups: KB) -> None:
    """Issue 30, class 8, through the dialogue manager: the form's question asks for the age and
    whether Nina likes tea; one answer gives both, the yes said inside it."""
    config = json.dumps({"question": "How old are you, and do you like tea?",
                         "result_schema_properties": {"age": PROPERTIES["age"], "likes_tea": {"type": "boolean"}}})
    manager = DialogueManager(DialogueEngine(cups))
    both = manager.start(ASK_ROLE, configuration=config)
    (result,) = talk(manager, both.id, "I'm 34 and yes I love tea")
    assert (result.response, result.dialogue_terminal) == ("Thank you.", True)
    assert json.loads(result.results or "") == {"age": 34, "likes_tea": True} and result.intents == ()
    # Said the other way round, with a no.
    other = manager.start(ASK_ROLE, configuration=config)
    (result,) = talk(manager, other.id, "no I don't, and I'm thirty")
    assert result.dialogue_terminal and json.loads(result.results or "") == {"likes_tea": False, "age": 30}
    # After the age alone, the robot asks for the rest by itself, and a bare answer fills it.
    step = manager.start(ASK_ROLE, configuration=config)
    first, second = talk(manager, step.id, "34", "yep")
    assert first.response == "And likes tea: yes or no?" and not first.dialogue_terminal
    assert second.dialogue_terminal and json.loads(second.results or "") == {"age": 34, "likes_tea": True}


def test_a_correction_before_the_end(cups: KB) -> None:
    manager = DialogueManager(DialogueEngine(cups))
    d = manager.start(ASK_ROLE, configuration=CONFIG)
    _first, second = talk(manager, d.id, "33", "no, I'm 34")
    assert json.loads(second.results or "") == {"age": 34} and not second.dialogue_terminal
    assert second.trace is not None and "age: corrected with 34" in second.trace.notes[0]


def test_cancel_ends_with_what_was_obtained(cups: KB) -> None:
    manager = DialogueManager(DialogueEngine(cups))
    d = manager.start(ASK_ROLE, configuration=CONFIG)
    _first, cancelled = talk(manager, d.id, "I am 40", "never mind")
    assert cancelled.dialogue_terminal and json.loads(cancelled.results or "") == {"age": 40}
    assert cancelled.response == "OK, never mind."


def test_not_understood_asks_again_with_raw_user_input(cups: KB) -> None:
    manager = DialogueManager(DialogueEngine(cups))
    d = manager.start(ASK_ROLE, configuration=CONFIG)
    (result,) = talk(manager, d.id, "the weather is lovely")
    assert result.response == "Sorry, I did not get that. How old are you, and which cup?"
    assert [i.intent for i in result.intents] == [RAW_USER_INPUT] and not result.dialogue_terminal


def test_a_scripted_model_fills_the_form_with_a_repair(cups: KB) -> None:
    model = ScriptedModel([
        "not json at all",
        answer({"age": 34, "cup": "cup_blue"}, "Thanks!"),
    ])
    manager = DialogueManager(DialogueEngine(cups, model))
    d = manager.start(ASK_ROLE, configuration=CONFIG)
    (result,) = talk(manager, d.id, "Thirty-four, and the blue one.")
    assert result.dialogue_terminal and json.loads(result.results or "") == {"age": 34, "cup": "cup_blue"}
    assert result.backend == "scripted" and result.response == "Thank you."
    schema = model.requests[0].schema
    cup = schema["properties"]["answers"]["properties"]["cup"]["anyOf"][0]
    assert set(cup["enum"]) == {"cup_red", "cup_blue"}  # the entity field is an enum of KB ids
    assert schema["properties"]["answers"]["properties"]["age"]["anyOf"][0] == PROPERTIES["age"]
    assert model.requests[1].repair and "contains no JSON object" in model.requests[1].messages[-1].content
    trace = result.trace
    assert trace is not None and len(trace.exchanges) == 2 and trace.repaired
    assert trace.exchanges[0].raw_answer == "not json at all" and trace.validation_errors


def test_a_model_value_out_of_bounds_is_asked_again_and_a_name_is_resolved(cups: KB) -> None:
    model = ScriptedModel([
        answer({"age": 200, "cup": None}),
        answer({"age": 34, "cup": "the red cup"}),  # a name, not an id: resolved against the KB
    ])
    manager = DialogueManager(DialogueEngine(cups, model))
    d = manager.start(ASK_ROLE, configuration=CONFIG)
    first, second = talk(manager, d.id, "two hundred", "34, red")
    assert first.response.startswith("That is not a possible age") and not first.dialogue_terminal
    assert json.loads(second.results or "") == {"age": 34, "cup": "cup_red"}
    assert "Fields filled so far: {}" in model.requests[0].messages[-1].content
    assert "Fields still missing: age, cup" in model.requests[0].messages[-1].content


def test_an_unknown_id_from_the_model_is_repaired_then_falls_back(cups: KB) -> None:
    model = ScriptedModel([answer({"cup": "cup_gold"}), answer({"cup": "cup_silver"})])
    manager = DialogueManager(DialogueEngine(cups, model))
    d = manager.start(ASK_ROLE, configuration=CONFIG)
    (result,) = talk(manager, d.id, "the golden cup")
    assert "gave no valid answer twice" in result.error_msg and not result.dialogue_terminal
    assert result.response.endswith("How old are you, and which cup?")
    assert "cup_gold" in model.requests[1].messages[-1].content


def test_the_model_cancels(cups: KB) -> None:
    manager = DialogueManager(DialogueEngine(cups, ScriptedModel([answer({}, cancel=True)])))
    d = manager.start(ASK_ROLE, configuration=CONFIG)
    (result,) = talk(manager, d.id, "laisse tomber")
    assert result.dialogue_terminal and result.results == "{}"


def test_hybrid_reads_with_the_rules_first_and_the_model_for_the_rest(cups: KB) -> None:
    inner = ScriptedModel([answer({"age": 34})])
    manager = DialogueManager(DialogueEngine(cups, HybridModel(inner)))
    d = manager.start(ASK_ROLE, configuration=CONFIG)
    first, second = talk(manager, d.id, "the red cup", "I'm in my mid thirties, thirty-four-ish")
    assert first.backend == "rules" and len(inner.requests) == 1  # the second turn only
    assert second.backend == "scripted" and json.loads(second.results or "") == {"cup": "cup_red", "age": 34}
    # The model was told what the rules had already filled.
    assert '"cup": "cup_red"' in inner.requests[0].messages[-1].content


def test_another_language_the_model_answers_in_it_and_the_rules_hand_over(cups: KB) -> None:
    model = ScriptedModel([answer({"age": 34}, "Merci ! Et quelle tasse ?")])
    manager = DialogueManager(DialogueEngine(cups, HybridModel(model)))
    d = manager.start(ASK_ROLE, locale="fr_FR", configuration=CONFIG)
    (result,) = talk(manager, d.id, "J'ai trente-quatre ans")
    assert result.response == "Merci ! Et quelle tasse ?" and json.loads(result.results or "") == {"age": 34}
    assert "Answer the person in French" in model.requests[0].messages[-1].content
    rules_only = DialogueManager(DialogueEngine(cups))
    d = rules_only.start(ASK_ROLE, locale="fr_FR", configuration=CONFIG)
    (handed,) = talk(rules_only, d.id, "non, j'ai 34 ans")
    assert handed.response == "" and "English only" in handed.error_msg and handed.results == "{}"
    assert handed.intents[0].intent == RAW_USER_INPUT and handed.intents[0].data["locale"] == "fr_FR"
    assert handed.trace is not None and handed.trace.answered_by == "handover"


def test_a_stateless_turn_reads_the_form_from_the_history(cups: KB) -> None:
    manager = DialogueManager(DialogueEngine(cups))
    history = [Utterance(ASSISTANT_USER_ID, "How old are you, and which cup?"), Utterance(NINA, "I'm 34"),
               Utterance(ASSISTANT_USER_ID, "Which cup?")]

    async def run() -> TurnResult:
        return await manager.interact(NINA, "the blue cup", dialogue_id="dm-1", history=history, role=ASK_ROLE,
                                      configuration=CONFIG)

    result = asyncio.run(run())
    assert result.dialogue_terminal and json.loads(result.results or "") == {"age": 34, "cup": "cup_blue"}
    assert "dm-1" not in manager.ids()  # nothing stored
    assert result.trace is not None and result.trace.shape == "4.0"
    assert manager.traces.recent("dm-1") == [result.trace]


def test_the_deadline_answers_and_keeps_the_form(cups: KB) -> None:
    model = ScriptedModel([answer({"age": 34})], delay=2.0)
    manager = DialogueManager(DialogueEngine(cups, model, EngineConfig(deadline=0.2)))
    d = manager.start(ASK_ROLE, configuration=CONFIG)
    (result,) = talk(manager, d.id, "34")
    assert "deadline" in result.error_msg and not result.dialogue_terminal
    assert json.loads(manager.get(d.id).role_state)["values"] == {}


def test_an_unreadable_stored_form_is_read_again_from_the_history(cups: KB) -> None:
    manager = DialogueManager(DialogueEngine(cups))
    d = manager.start(ASK_ROLE, configuration=CONFIG)
    talk(manager, d.id, "I'm 34")
    manager.store.save(replace(manager.get(d.id), role_state='{"values": 3}'))
    (result,) = talk(manager, d.id, "the red cup")
    assert json.loads(result.results or "") == {"age": 34, "cup": "cup_red"} and result.dialogue_terminal
    assert result.trace is not None and any("could not be read" in n for n in result.trace.notes)


def test_a_form_with_no_required_field_ends_after_one_answer(cups: KB) -> None:
    manager = DialogueManager(DialogueEngine(cups))
    configuration = json.dumps({"question": "Anything to add?", "required": [],
                                "result_schema_properties": {"age": PROPERTIES["age"], "tea": PROPERTIES["tea"]}})
    d = manager.start(ASK_ROLE, configuration=configuration)
    (result,) = talk(manager, d.id, "I'm 40")
    assert result.dialogue_terminal and json.loads(result.results or "") == {"age": 40}


def test_a_system_update_or_the_robots_own_words_are_no_answer(cups: KB) -> None:
    """A `__system__` input ("the battery is at 40 percent") filled the age with 40 and ended the form;
    it is no answer of the person (nor is `__assistant__`): the form is unchanged, the question asked again
    after the system update."""
    manager = DialogueManager(DialogueEngine(cups))
    d = manager.start(ASK_ROLE, configuration=CONFIG)

    async def run() -> list[TurnResult]:
        return [await manager.interact(SYSTEM_USER_ID, "The battery is at 40 percent", dialogue_id=d.id),
                await manager.interact(ASSISTANT_USER_ID, "I am 30 years old", dialogue_id=d.id),
                await manager.interact(NINA, "I'm 34", dialogue_id=d.id)]

    system, assistant, person = asyncio.run(run())
    assert (system.dialogue_terminal, system.results) == (False, "{}") and system.intents == ()
    assert system.response == "How old are you, and which cup?"
    # The robot's own words are recorded, never answered (dialogue.sessions.entries).
    assert (assistant.response, assistant.intents, assistant.dialogue_terminal) == ("", (), None)
    assert json.loads(person.results or "") == {"age": 34}
    # The same in the 4.0 shape, whose input is the history's last utterance.
    history = [Utterance(ASSISTANT_USER_ID, "How old are you, and which cup?"), Utterance(NINA, "I'm 34")]
    stateless = asyncio.run(manager.interact(SYSTEM_USER_ID, "Battery at 40 percent", dialogue_id="dm",
                                             history=history, role=ASK_ROLE, configuration=CONFIG))
    assert json.loads(stateless.results or "") == {"age": 34} and not stateless.dialogue_terminal


def test_results_are_json_and_exact_or_the_robot_asks_again(cups: KB) -> None:
    manager = DialogueManager(DialogueEngine(cups))
    config = json.dumps({"question": "How much, and how many?",
                         "result_schema_properties": {"amount": {"type": "number"}, "n": {"type": "integer"}}})
    started = manager.start(ASK_ROLE, configuration=config)
    huge, ok = talk(manager, started.id, "the amount is " + "9" * 400, "the amount is 2.5")
    assert huge.response.startswith("That is not a possible amount: input should have at most 100 digits.")
    assert json.loads(huge.results or "") == {} and not huge.dialogue_terminal
    assert json.loads(ok.results or "") == {"amount": 2.5}
    (done,) = talk(manager, started.id, "1,000,000,000,000,000,000,000,000")
    assert done.dialogue_terminal and json.loads(done.results or "") == {"amount": 2.5, "n": 10**24}


def test_the_model_is_told_the_robots_name_from_the_kb(cups: KB) -> None:
    # the same name the rules answer with: the scene's label of `myself`, not the configured one
    cups.update(['myself rdfs:label "Pebble"'])
    model = ScriptedModel([answer({"age": 34, "cup": "cup_blue"}, "Thanks!")])
    manager = DialogueManager(DialogueEngine(cups, model))
    d = manager.start(ASK_ROLE, configuration=CONFIG)
    talk(manager, d.id, "Thirty-four, and the blue one.")
    system = model.requests[0].messages[0]
    assert system.role == "system" and system.content.startswith("You are Pebble, a social robot.")
