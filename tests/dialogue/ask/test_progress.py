"""The form after each answer and the robot's next line."""

from __future__ import annotations

from dialogue.ask.form import AskForm, Clarifying
from dialogue.ask.progress import MAX_TRIES, advance, opening_state, question_for
from dialogue.reference.lexicon import Lexicon
from dialogue.understanding.followups.form import Reading, read_answer
from tests.dialogue.ask.conftest import NINA, form_of


def test_asks_only_for_what_is_missing_then_ends(form: AskForm, lexicon: Lexicon) -> None:
    state = opening_state(form)
    assert state.asked == "age"
    state, line = advance(form, state, Reading(values={"age": 30, "name": "Nina"}), lexicon)
    assert state.asked == "colour" and line == "Which colour: red, green, light blue or blue?"
    state, line = advance(form, state, Reading(values={"colour": "red"}), lexicon)
    assert line == "Which cup: the blue cup or the red cup?"
    state, line = advance(form, state, Reading(values={"cup": "cup_red"}), lexicon)
    assert line == "And tea: yes or no?"
    state, line = advance(form, state, Reading(values={"tea": True, "friend": "person_oliver"}), lexicon)
    assert (state.status, line, state.asked) == ("done", "Thank you.", None)


def test_a_problem_is_said_back_and_the_field_asked_again(lexicon: Lexicon) -> None:
    form = form_of(age={"type": "integer", "minimum": 0, "maximum": 130})
    state, line = advance(form, opening_state(form), Reading(problems={"age": "Input should be less than or equal to 130"}))
    assert line == "That is not a possible age: it must be at least 0 and at most 130. A few questions?"
    assert state.tries == {"age": 1} and state.status == "open"


def test_a_field_never_obtained_is_given_up_and_omitted(lexicon: Lexicon) -> None:
    form = form_of(age={"type": "integer"}, name={"type": "string"})
    state = opening_state(form)
    for _ in range(MAX_TRIES - 1):
        state, line = advance(form, state, Reading())
        assert line.startswith("Sorry, I did not get that.") and state.asked == "age"
    state, line = advance(form, state, Reading())
    assert state.given_up == ["age"] and state.asked == "name" and line.endswith("And what is your name?")
    state, line = advance(form, state, Reading(values={"name": "Nina"}))
    assert state.status == "done" and state.results() == '{"name": "Nina"}'


def test_skip_cancel_and_clarify(form: AskForm, lexicon: Lexicon) -> None:
    state, line = advance(form, opening_state(form), Reading(skipped=["age"]))
    assert state.given_up == ["age"] and state.asked == "name"
    state, line = advance(form, state, Reading(cancel=True))
    assert (state.status, line) == ("cancelled", "OK, never mind.")
    cups = tuple(lexicon.snapshot.entities[i] for i in ("cup_red", "cup_blue"))
    reading = Reading(clarify=Clarifying(field="cup", candidates=["cup_red", "cup_blue"]), clarify_options=cups)
    state, line = advance(form, opening_state(form), reading, lexicon, cups)
    assert state.asked == "cup" and line == "Which cup do you mean: the red cup or the blue cup?"


def test_questions_by_kind_and_description() -> None:
    form = form_of(pets={"type": "boolean"}, size={"type": "number", "description": "How tall are you?"})
    assert question_for(form, "pets") == "A few questions? Please say yes or no."
    assert question_for(form, "size") == "How tall are you?"


def test_a_fraction_for_an_integer_is_said_as_such_not_as_the_bounds() -> None:
    """ "three point five" for an integer field with a minimum was answered "it must be at least 0"."""
    form = form_of(children={"type": "integer", "minimum": 0})
    _value, problem = form.field("children").check(3.5)
    assert problem is not None
    _state, line = advance(form, opening_state(form), Reading(problems={"children": problem}))
    assert line == "That is not a possible children: it must be a whole number. A few questions?"


def test_an_enum_asked_again_says_its_values(lexicon: Lexicon) -> None:
    """The form's question does not list an enum's values: asked again, the robot says them."""
    form = form_of(size={"enum": ["small", "medium", "large"]})
    _state, line = advance(form, opening_state(form), Reading())
    assert line == "Sorry, I did not get that. A few questions? Please say small, medium or large."


def test_the_entities_listed_in_a_question_are_offered(form: AskForm, lexicon: Lexicon) -> None:
    """ "Which cup: the blue cup or the red cup?" then "the second one": the listed cups are the
    choices, in the order said (an ordinal was understood only after a clarifying question)."""
    state, line = advance(form, opening_state(form), Reading(values={"age": 30, "name": "Nina", "colour": "red"}),
                          lexicon)
    assert line == "Which cup: the blue cup or the red cup?"
    assert state.clarifying == Clarifying(field="cup", candidates=["cup_blue", "cup_red"])
    reading = read_answer(form, state, "the second one", lexicon, NINA)
    assert reading.values == {"cup": "cup_red"}
