import pytest
from hypothesis import given
from hypothesis import strategies as st

from dialogue.history import ASSISTANT_USER_ID, SYSTEM_USER_ID, History, Utterance, role_of


def test_roles_of_special_user_ids() -> None:
    assert role_of(ASSISTANT_USER_ID) == "assistant"
    assert role_of(SYSTEM_USER_ID) == "system"
    assert role_of("person_a") == "user"


def test_history_is_bounded_by_turns_and_characters() -> None:
    history = History(max_turns=3, max_chars=100)
    for i in range(10):
        history.add("p", f"turn {i}")
    assert [u.text for u in history] == ["turn 7", "turn 8", "turn 9"]
    history.add("p", "x" * 95)
    assert [u.text for u in history] == ["x" * 95]
    history.add("p", "y" * 500)  # one oversized utterance is still kept (the latest is never lost)
    assert len(history) == 1
    with pytest.raises(ValueError, match="positive"):
        History(max_turns=0)


@given(st.integers(1, 6), st.integers(1, 60), st.lists(st.text(max_size=30), max_size=40))
def test_the_kept_utterances_are_the_latest_that_fit(max_turns: int, max_chars: int, texts: list[str]) -> None:
    history = History(max_turns, max_chars)
    said: list[str] = []  # a blank text says nothing and is never kept
    for text in texts:
        history.add("p", text)
        if text.strip():
            said.append(text)
        # what must be kept: the latest `max_turns`, then the oldest dropped while over `max_chars`
        # (the latest one always)
        expected = said[-max_turns:]
        while len(expected) > 1 and sum(map(len, expected)) > max_chars:
            expected.pop(0)
        assert [u.text for u in history] == expected


@given(st.integers(1, 6), st.integers(1, 60),
       st.lists(st.tuples(st.sampled_from(["p", ASSISTANT_USER_ID]), st.text(max_size=30)), max_size=40))
def test_a_history_made_at_once_keeps_what_adding_one_by_one_keeps(
        max_turns: int, max_chars: int, said: list[tuple[str, str]]) -> None:
    added = History(max_turns, max_chars)
    for speaker, text in said:
        added.add(speaker, text)
    made = History.of([Utterance(s, t) for s, t in said], max_turns, max_chars)
    assert made.snapshot() == added.snapshot()
    # and both go on the same way
    made.add("p", "x" * max_chars)
    added.add("p", "x" * max_chars)
    assert made.snapshot() == added.snapshot()
