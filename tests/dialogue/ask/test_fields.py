"""One finder per kind of field: what a clause says for a field, or nothing."""

from __future__ import annotations

import json
from typing import Any

from dialogue.ask import fields
from dialogue.ask.fields import ReadContext, find
from dialogue.ask.form import AskForm, FormState
from dialogue.reference.lexicon import Lexicon
from dialogue.understanding.followups.form import read_answer
from tests.dialogue.ask.conftest import NINA, form_of
from tests.dialogue.conftest import english, lexicon_of, scene_kb


class Clause:
    """Clauses read in English (dialogue.ask.fields.Clause reads them in a language)."""

    @staticmethod
    def of(text: str) -> fields.Clause:
        return fields.Clause.of(english(), text)


def found(form: AskForm, lexicon: Lexicon, name: str, text: str, asked: str | None = None,
          clarifying: dict[str, list[str]] | None = None) -> Any:
    hit = find(form.field(name), Clause.of(text), ReadContext(lexicon, NINA, asked, frozenset(), clarifying or {}))
    if hit is None:
        return None
    if hit.candidates:
        return tuple(e.id for e in hit.candidates)
    return "problem" if hit.problem else hit.value


def test_numbers_in_digits_and_words(form: AskForm, lexicon: Lexicon) -> None:
    assert Clause.of("twenty-three").numbers == (23.0,)
    assert Clause.of("a hundred and five").numbers == (105.0,)
    assert Clause.of("minus three").numbers == (-3.0,)
    assert Clause.of("3.5 metres").numbers == (3.5,)
    assert Clause.of("the 1st one").numbers == ()  # an ordinal is no number, "one" here a pronoun
    assert Clause.of("the red one").numbers == () and Clause.of("one").numbers == (1.0,)
    assert found(form, lexicon, "age", "I'm thirty-four") == 34
    assert found(form, lexicon, "age", "34 or 35") is None  # two numbers: which?
    assert found(form, lexicon, "age", "two hundred") == "problem"  # above the maximum


def test_booleans_answer_only_the_field_asked(form: AskForm, lexicon: Lexicon) -> None:
    for text, value in [("yes", True), ("sure", True), ("of course", True), ("nope", False), ("no thanks", False),
                        ("I don't", False)]:
        assert found(form, lexicon, "tea", text, asked="tea") is value, text
    assert found(form, lexicon, "tea", "yes") is None  # nobody asked about tea
    assert found(form, lexicon, "tea", "yes and no", asked="tea") is None


def test_a_yes_or_no_opening_a_clause_answers_a_field_the_question_covered(form: AskForm, lexicon: Lexicon) -> None:
    asked_with_the_rest = ReadContext(lexicon, NINA, "age", covered=frozenset({"tea", "name"}))
    for text, value in [("yes I love tea", True), ("no I don't", False), ("well, of course not", False),
                        ("of course", True), ("I don't", False)]:
        hit = find(form.field("tea"), Clause.of(text), asked_with_the_rest)
        assert hit is not None and hit.value is value, text
    # A yes or no inside the clause, not opening it, is no answer to a field not asked by itself.
    assert find(form.field("tea"), Clause.of("I think Bob doesn't"), asked_with_the_rest) is None
    # Nor is a free string read for a covered field: only yes/no fields take this reading.
    assert find(form.field("name"), Clause.of("yes"), asked_with_the_rest) is None


def test_enum_values_longest_first(form: AskForm, lexicon: Lexicon) -> None:
    assert found(form, lexicon, "colour", "light blue please") == "light blue"
    assert found(form, lexicon, "colour", "I like blue") == "blue"
    assert found(form, lexicon, "colour", "purple") is None


def test_free_string_is_what_follows_the_lead_in(form: AskForm, lexicon: Lexicon) -> None:
    assert found(form, lexicon, "name", "It's Nina Simone.", asked="name") == "Nina Simone"
    assert found(form, lexicon, "name", "Bob") is None  # a free string only for the field asked or named


def test_entities_are_kb_ids_with_candidates_when_ambiguous(form: AskForm, lexicon: Lexicon) -> None:
    assert found(form, lexicon, "cup", "I'd like the red cup") == "cup_red"
    assert set(found(form, lexicon, "cup", "the cup")) == {"cup_red", "cup_blue"}
    assert found(form, lexicon, "cup", "the red one", clarifying={"cup": ["cup_red", "cup_blue"]}) == "cup_red"
    assert found(form, lexicon, "cup", "the second", clarifying={"cup": ["cup_red", "cup_blue"]}) == "cup_blue"
    assert found(form, lexicon, "cup", "cup_blue") == "cup_blue"
    assert found(form, lexicon, "cup", "the black phone") == "problem"  # a thing, but not a cup
    assert found(form, lexicon, "friend", "Oliver") == "person_oliver"
    assert found(form, lexicon, "friend", "the red cup") == "problem"
    assert found(form, lexicon, "cup", "a giraffe") is None


def test_an_id_that_is_also_a_word_does_not_outrank_the_noun_phrase(form: AskForm) -> None:
    """The demo scene names its cup `cup`: "the blue cup" is still the blue one, "the cup" any of three."""
    kb = scene_kb("two_cups", "cup rdf:type dbr:Cup", "cup isOn table_2", "myself sees cup")
    lexicon = lexicon_of(kb)
    assert found(form, lexicon, "cup", "the blue cup please") == "cup_blue"
    assert found(form, lexicon, "cup", "I'd like the red cup") == "cup_red"
    assert set(found(form, lexicon, "cup", "the cup")) == {"cup", "cup_red", "cup_blue"}
    assert found(form, lexicon, "cup", "cup_blue") == "cup_blue"  # an id typed as it is
    kb.close()


def test_negated_and_idiomatic_yes_no(form: AskForm, lexicon: Lexicon) -> None:
    """ "absolutely not" was not understood (a yes word and a no word), "why not" read as a no."""
    for text, value in [("absolutely not", False), ("certainly not", False), ("of course not", False),
                        ("that's not true", False), ("not right", False), ("why not", True),
                        ("no problem", True), ("I don't mind", True), ("I'd love to", True), ("I think so", True),
                        ("I don't think so", False), ("I'd rather not", False), ("not really", False)]:
        assert found(form, lexicon, "tea", text, asked="tea") is value, text


def test_me_in_a_person_field_is_the_speaker(form: AskForm, lexicon: Lexicon) -> None:
    """ "Who should I bring it to?" "To me." was not understood."""
    for text in ("me", "to me please", "myself", "bring it to me"):
        assert found(form, lexicon, "friend", text) == NINA, text
    assert found(form, lexicon, "friend", "not me") is None
    reading = read_answer(form, FormState(asked="friend"), "Oliver, not me", lexicon, NINA)
    assert reading.values == {"friend": "person_oliver"}
    assert found(form, lexicon, "cup", "me") is None  # a cup field: "me" names no cup


def test_an_enum_value_said_by_one_of_its_words(lexicon: Lexicon) -> None:
    """ "chocolate" for "hot chocolate" was not understood; a word of exactly one value names it, when
    the field is the one asked (a single word is weak evidence)."""
    form = form_of(drink={"enum": ["tea", "orange juice", "apple juice", "hot chocolate"]})
    assert found(form, lexicon, "drink", "chocolate please", asked="drink") == "hot chocolate"
    assert found(form, lexicon, "drink", "the orange one", asked="drink") == "orange juice"
    assert found(form, lexicon, "drink", "juice", asked="drink") is None  # two juices: which?
    assert found(form, lexicon, "drink", "something hot", asked="drink") == "hot chocolate"
    assert found(form, lexicon, "drink", "a glass of water", asked="drink") is None
    assert found(form, lexicon, "drink", "chocolate please") is None  # not asked


def test_numbers_are_read_exactly_or_refused(lexicon: Lexicon) -> None:
    """Issue 26, rerun of attack 8: 400 nines in a number field gave ``Infinity`` (no JSON), and
    "1,000,000,000,000,000,000,000,000" in an integer field 999999999999999983222784."""
    form = form_of(amount={"type": "number"}, n={"type": "integer"})
    assert found(form, lexicon, "n", "1,000,000,000,000,000,000,000,000") == 10**24
    # a float whose JSON text is the number said ("1e+24"), or the integer itself
    assert json.dumps(found(form, lexicon, "amount", "1,000,000,000,000,000,000,000,000")) in (
        "1e+24", "1000000000000000000000000")
    assert found(form, lexicon, "amount", "12345678901234567") == 12345678901234567
    assert found(form, lexicon, "amount", "3.5") == 3.5 and found(form, lexicon, "n", "three") == 3
    assert found(form, lexicon, "amount", "9" * 400) == "problem"  # past 100 digits, never Infinity
    assert found(form, lexicon, "amount", "-" + "9" * 400) == "problem"
    assert found(form, lexicon, "n", "9" * 400) == "problem"
    assert found(form, lexicon, "n", "12345678901234567 and a half") == "problem"  # not a whole number
    assert found(form, lexicon, "amount", "12345678901234567.5") == "problem"  # a float would round it
