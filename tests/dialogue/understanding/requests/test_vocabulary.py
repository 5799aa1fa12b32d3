"""The words the grammar of requests reads, gathered once per language."""

from dialogue.understanding.requests.vocabulary import Grammar
from tests.dialogue.conftest import english


def test_the_words_are_gathered_once_per_language() -> None:
    lang = english()
    assert lang.derived(Grammar) is lang.derived(Grammar)


def test_they_are_the_language_s_own() -> None:
    g = english().derived(Grammar)
    assert g.conditions.table == english().requests.conditions
    assert ("next",) not in g.joined and g.joined[("next", "to")] == "beside"
    assert [act for act, _ in g.talk] == ["farewell", "abilities", "joke"]
