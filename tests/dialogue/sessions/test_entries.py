"""Which dialogue entries are answered, and the checks every entry passes first."""

from __future__ import annotations

import pytest

from dialogue.errors import SessionError
from dialogue.history import Utterance
from dialogue.sessions.entries import answers, check_texts, check_utterance, entry_locale, said_nothing


@pytest.mark.parametrize(("user_id", "text", "expected", "answered"), [
    ("person_alice", "pick up the cup", True, True),
    ("person_alice", "pick up the cup", False, False),
    ("person_alice", "  ", True, False),          # nothing said
    ("__system__", "Tom came in", True, True),    # the role may have a line for it
    ("__system__", "", True, True),               # a prompt to speak (the ask role's question)
    ("__system__", "Tom came in", False, False),
    ("__assistant__", "I fetched it.", True, False),  # the robot's own words: never answered
])
def test_which_entries_are_answered(user_id: str, text: str, expected: bool, answered: bool) -> None:
    assert answers(user_id, text, expected) is answered


def test_a_blank_utterance_is_refused_where_an_edge_asks_for_words() -> None:
    assert check_utterance("hi") == "hi"
    with pytest.raises(SessionError, match="empty or blank"):
        check_utterance(" \n")


def test_locales_and_texts_are_checked() -> None:
    assert entry_locale("en-gb") == "en_GB" and entry_locale("") is None
    with pytest.raises(SessionError, match="not a language tag"):
        entry_locale("english please")
    with pytest.raises(SessionError, match=r"history turn 0.*not valid Unicode"):
        check_texts("p", "hi", None, [Utterance("p", "bad \ud800")])


def test_nothing_said_is_a_blank_entry_that_is_no_system_update() -> None:
    for user in ("person_alice", "__assistant__"):
        assert said_nothing(user, "") and said_nothing(user, " \n\t")
        assert not said_nothing(user, "hi")
    assert not said_nothing("__system__", "") and not answers("person_alice", " ", True)
