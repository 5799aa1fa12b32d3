"""The offline reading of answers: several fields at once, corrections, refusals, cancel."""

from __future__ import annotations

from dialogue.ask.form import AskForm, FormState
from dialogue.reference.lexicon import Lexicon
from dialogue.understanding.followups.form import read_answer
from tests.dialogue.ask.conftest import NINA, form_of


def test_several_fields_in_one_answer(form: AskForm, lexicon: Lexicon) -> None:
    reading = read_answer(form, FormState(asked="age"),
                          "I'm twenty-three, my name is Nina and my favourite colour is light blue", lexicon, NINA)
    assert reading.values == {"age": 23, "name": "Nina", "colour": "light blue"}
    assert reading.understood and not reading.problems


def test_a_value_goes_to_the_field_asked_first(lexicon: Lexicon) -> None:
    form = form_of(age={"type": "integer"}, children={"type": "integer"})
    assert read_answer(form, FormState(asked="children"), "2", lexicon, NINA).values == {"children": 2}
    # Not asked, both open: a bare number is not guessed.
    assert read_answer(form, FormState(asked=None), "2", lexicon, NINA).values == {}
    # One open field of its type: it goes there.
    assert read_answer(form, FormState(values={"age": 30}, asked=None), "2", lexicon, NINA).values == {"children": 2}


def test_a_correction_replaces_a_filled_field(form: AskForm, lexicon: Lexicon) -> None:
    state = FormState(values={"age": 33}, asked="name")
    reading = read_answer(form, state, "no, I'm 34", lexicon, NINA)
    assert reading.values == {"age": 34}
    assert any("age: corrected with 34" in note for note in reading.notes)
    # Without "no"/"actually", a number does not overwrite a filled field nobody named.
    assert read_answer(form, FormState(values={"age": 33}, asked="cup"), "34", lexicon, NINA).values == {}
    assert read_answer(form, FormState(values={"age": 33}, asked="cup"), "actually 34", lexicon, NINA).values == {
        "age": 34}
    assert read_answer(form, FormState(values={"age": 33}, asked="cup"), "my age is 35", lexicon, NINA).values == {
        "age": 35}


def test_a_bare_no_answers_the_yes_no_question(form: AskForm, lexicon: Lexicon) -> None:
    assert read_answer(form, FormState(asked="tea"), "no", lexicon, NINA).values == {"tea": False}
    reading = read_answer(form, FormState(values={"age": 20}, asked="tea"), "no, I'm 21", lexicon, NINA)
    assert reading.values == {"tea": False, "age": 21}


def test_cancel_skip_and_nonsense(form: AskForm, lexicon: Lexicon) -> None:
    for text in ("never mind", "Forget it.", "I don't want to answer", "cancel"):
        assert read_answer(form, FormState(asked="age"), text, lexicon, NINA).cancel, text
    skipped = read_answer(form, FormState(asked="age"), "I don't know", lexicon, NINA)
    assert skipped.skipped == ["age"] and not skipped.cancel
    nothing = read_answer(form, FormState(asked="age"), "the weather is lovely", lexicon, NINA)
    assert not nothing.understood


def test_out_of_bounds_is_a_problem_and_ambiguity_a_clarification(form: AskForm, lexicon: Lexicon) -> None:
    reading = read_answer(form, FormState(asked="age"), "I'm 200", lexicon, NINA)
    assert reading.values == {} and "age" in reading.problems
    ambiguous = read_answer(form, FormState(asked="cup"), "the cup please", lexicon, NINA)
    assert ambiguous.clarify is not None and ambiguous.clarify.field == "cup"
    assert set(ambiguous.clarify.candidates) == {"cup_red", "cup_blue"}
    state = FormState(asked="cup", clarifying=ambiguous.clarify)
    assert read_answer(form, state, "the blue one", lexicon, NINA).values == {"cup": "cup_blue"}


def test_a_number_said_with_and_or_a_thousands_comma_is_one_number(lexicon: Lexicon) -> None:
    """ "a hundred and five" was cut into two clauses at "and" (and read as 5), "1,500" at the comma."""
    form = form_of(n={"type": "number"}, name={"type": "string"})
    for text, value in [("a hundred and five", 105), ("one hundred and twenty-three", 123), ("1,500", 1500),
                        ("two and a half", 2.5), ("about 3,250 and my name is Nina", 3250)]:
        assert read_answer(form, FormState(asked="n"), text, lexicon, NINA).values.get("n") == value, text
    reading = read_answer(form, FormState(asked="n"), "twelve, and my name is Nina", lexicon, NINA)
    assert reading.values == {"n": 12, "name": "Nina"}


def test_sure_why_not_is_a_yes(form: AskForm, lexicon: Lexicon) -> None:
    assert read_answer(form, FormState(asked="tea"), "sure, why not", lexicon, NINA).values == {"tea": True}


def test_a_question_back_or_a_refusal_is_no_free_string(lexicon: Lexicon) -> None:
    """ "What is your name?" "why do you want to know?" filled the name with those words."""
    form = form_of(name={"type": "string"}, age={"type": "integer"})
    for text in ("why do you want to know?", "what?", "can you repeat the question", "what do you mean",
                 "pardon", "how do you spell it?"):
        assert read_answer(form, FormState(asked="name"), text, lexicon, NINA).values == {}, text
    for text in ("I'd rather not tell you", "I prefer not to say", "I won't tell you"):
        assert read_answer(form, FormState(asked="name"), text, lexicon, NINA).skipped == ["name"], text
    assert read_answer(form, FormState(asked="name"), "it's Will", lexicon, NINA).values == {"name": "Will"}


def test_a_yes_or_no_said_among_other_answers_fills_the_yes_no_field(lexicon: Lexicon) -> None:
    """Issue 30, class 8: the form's own question asked for every field, so a yes or no opening a
    clause of the answer fills the one yes/no field still open, whatever it is called."""
    form = form_of(age={"type": "integer"}, likes_tea={"type": "boolean"})
    asked = FormState(asked="age")
    for text, values in [("I'm 34 and yes I love tea", {"age": 34, "likes_tea": True}),
                         ("34, yes", {"age": 34, "likes_tea": True}),
                         ("nope, and I am thirty", {"likes_tea": False, "age": 30}),
                         ("I am 34 and no I don't", {"age": 34, "likes_tea": False})]:
        assert read_answer(form, asked, text, lexicon, NINA).values == values, text
    # A "no" first may correct what was said before; then it answers no yes/no field by itself.
    assert read_answer(form, FormState(values={"likes_tea": True}, asked="age"), "no, I'm 34", lexicon,
                       NINA).values == {"age": 34}
    # Before any value there is nothing to correct: it is the answer.
    assert read_answer(form, asked, "no, I'm 34", lexicon, NINA).values == {"likes_tea": False, "age": 34}
    # Asked "And likes tea: yes or no?" after the age, the answer is read as before.
    assert read_answer(form, FormState(values={"age": 34}, asked="likes_tea"), "yes", lexicon, NINA).values == {
        "likes_tea": True}
    # A field's own question covers no other field: "yes" to the age question is no tea.
    own = form_of(age={"type": "integer", "description": "How old are you?"}, likes_tea={"type": "boolean"})
    assert read_answer(own, asked, "34, yes", lexicon, NINA).values == {"age": 34}
    # Two yes/no fields open: which one a bare yes answers is not guessed.
    two = form_of(age={"type": "integer"}, tea={"type": "boolean"}, coffee={"type": "boolean"})
    assert read_answer(two, asked, "34, yes", lexicon, NINA).values == {"age": 34}
