"""A table of phrases looked up at a text's start: the same ones, in the same order, as testing
each phrase in turn."""

from dialogue.understanding.speech.plain import starts
from dialogue.understanding.tables.prefixes import Prefixes


def test_prefixes_are_the_ones_the_words_start_with_in_the_table_s_order() -> None:
    table = Prefixes([("hello", "there"), ("hi",), ("hello",), ("good", "morning")])
    words = ["hello", "there", "robot"]
    assert table.of(words) == [("hello", "there"), ("hello",)]
    assert table.of(words) == [p for p in table if starts(words, p)]
    assert table.first(["hello"]) == ("hello",)  # "hello there" is longer than the words
    assert table.of(["say", "good", "morning"], at=1) == [("good", "morning")]
    assert table.of(["say", "good"], at=1) == [] and table.first(["say"], at=1) is None
    assert table.of([]) == [] and table.first(["bye"]) is None
    assert list(table) == list(table.table) and len(table) == 4


def test_a_table_with_an_empty_prefix_keeps_its_order() -> None:
    table = Prefixes([("hi",), (), ("hello",)])
    assert table.of(["hello"]) == [(), ("hello",)] and table.of(["hi"]) == [("hi",), ()]
    assert table.of([]) == [()]
