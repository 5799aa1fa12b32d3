import pytest

from dialogue.history import ASSISTANT_USER_ID, SYSTEM_USER_ID, History, role_of


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
