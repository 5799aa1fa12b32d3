"""Questions about the situation, on whole words."""

import pytest

from dialogue.understanding.parsed import Parse
from dialogue.understanding.questions import grammar
from dialogue.understanding.speech import plain
from kb import KB
from tests.dialogue.conftest import english
from tests.dialogue.understanding.test_interpret import say


def question(words: list[str]) -> Parse | None:
    return grammar.question(english(), words)


def expanded(text: str) -> list[str]:
    return plain.expanded(english(), text)


@pytest.mark.parametrize(
    ("text", "thing"),
    [
        ("how many mugs have we got", ("mugs",)),
        ("how many mugs do we have", ("mugs",)),
        ("how many green mugs have you got left", ("green", "mugs")),
        ("how many chairs are there in the hall", ("chairs", "in", "the", "hall")),
        ("how many mugs can you see", ("mugs",)),
        ("how many mugs are there", ("mugs",)),
        ("how many mugs", ("mugs",)),
    ],
)
def test_how_many_counts_the_words_before_the_questions_own_clause(text: str, thing: tuple[str, ...]) -> None:
    asked = question(text.split())
    assert asked is not None and asked.question == "how_many" and asked.slots == {"thing": thing}


def test_how_many_have_we_got_is_answered(office: KB) -> None:
    assert say(office, "how many mugs have we got").reply == (
        "I see two: the green mug and the yellow mug.")  # fmt: skip


@pytest.mark.parametrize(
    ("text", "place", "relation"),
    [
        ("what is next to the window", ("the", "window"), ("next", "to")),
        ("whats by the door", ("the", "door"), ("by",)),
        ("what's behind the sofa", ("the", "sofa"), ("behind",)),
    ],
)
def test_what_is_near_a_thing_asks_about_its_relations(
    text: str, place: tuple[str, ...], relation: tuple[str, ...]
) -> None:
    asked = question(expanded(text))
    assert asked is not None and asked.question == "what_near"
    assert asked.slots == {"place": place, "relation": relation}


def test_is_someone_about_asks_whether_they_are_there() -> None:
    asked = question(["is", "maria", "about"])
    assert asked is not None and (asked.question, asked.slots) == ("can_see", {"thing": ("maria",)})


def test_a_name_with_front_is_a_place_and_at_home_is_here(office: KB) -> None:
    assert question(expanded("whats on the front bench")).question == "what_on"
    assert question(expanded("what is in front of you")).question == "what_see"
    assert question(expanded("who is home")).question == "who_see"
    assert "Carol" in say(office, "who is at home right now?").reply


def test_where_has_a_thing_gone_said_with_is(office: KB) -> None:
    p = question(expanded("wheres my mug gone"))
    assert p is not None and (p.question, p.slots["thing"]) == ("where", ("my", "mug"))
    assert "desk" in say(office, "er wheres the green mug gone").reply
