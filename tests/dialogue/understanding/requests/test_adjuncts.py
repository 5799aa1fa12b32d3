"""The phrases of a request that say how, when or by which way: taken out of the words the roles
are read from."""

from dialogue.understanding.requests.adjuncts import adjuncts_of
from dialogue.understanding.requests.frames import Row, verb_index
from dialogue.understanding.requests.vocabulary import Grammar
from tests.dialogue.conftest import english


def _row(verb: str) -> Row:
    return next(row for phrase, row in verb_index(english())[verb] if phrase == (verb,))


def _adjuncts(verb: str, text: str) -> tuple[tuple[str, ...], tuple[tuple[str, ...], ...]]:
    return adjuncts_of(english().derived(Grammar), tuple(text.split()), _row(verb))


def test_a_phrase_of_time_or_manner_is_an_adjunct() -> None:
    assert _adjuncts("bring", "the fan for now") == (("the", "fan"), (("for", "now"),))
    assert _adjuncts("bring", "the cup carefully") == (("the", "cup"), (("carefully",),))


def test_a_phrase_of_the_row_s_own_preposition_is_a_role() -> None:
    assert _adjuncts("bring", "the cup to Ana") == (("the", "cup", "to", "Ana"), ())


def test_the_way_before_the_place_is_an_adjunct() -> None:
    words, found = _adjuncts("bring", "the cup through the main door to Ana")
    assert found == (("through", "the", "main", "door"),) and words == ("the", "cup", "to", "Ana")
