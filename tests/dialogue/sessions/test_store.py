import json

import pytest

from dialogue.history import ASSISTANT_USER_ID, Utterance
from dialogue.sessions.store import DEFAULT_DIALOGUE, DialogueState, MemorySessions, StateError


def test_state_round_trips_through_ascii_json() -> None:
    state = DialogueState(
        'id "}\n☕', "__default__", "en_GB", '{"a": 1}',
        (Utterance("person_alice", "grab the cup"), Utterance(ASSISTANT_USER_ID, "Which cup? \ud800")),
        1712345678.25,
    )
    text = state.to_json()
    assert text.isascii() and json.loads(text)["format"] == 1
    assert DialogueState.from_json(text) == state


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("{oops", "not JSON"),
        ("[]", "not an object of format 1"),
        ('{"format": 2}', "not an object of format 1"),
        ('{"format": 1, "id": "d", "role": "r", "configuration": "", "locale": null, "history": [{"speaker": 1, "text": "x"}], "last_used": 0}', "list of {speaker, text}"),
        ('{"format": 1, "id": 3, "role": "r", "configuration": "", "locale": null, "history": [], "last_used": 0}', "must be strings"),
        ('{"format": 1, "id": "d", "role": "r", "configuration": "", "locale": 5, "history": [], "last_used": 0}', "must be strings"),
        ('{"format": 1, "id": "d", "role": "r", "configuration": "", "locale": null, "history": [], "last_used": true}', "last_used must be a number"),
    ],
)
def test_unreadable_states_are_refused_with_the_reason(text: str, message: str) -> None:
    with pytest.raises(StateError, match=message):
        DialogueState.from_json(text)


def test_memory_sessions_bound_and_replace_only_semantics() -> None:
    sessions = MemorySessions(max_dialogues=3)
    sessions.save(DialogueState("ghost"))
    assert sessions.load("ghost") is None  # not created without create=True
    sessions.save(DialogueState(DEFAULT_DIALOGUE), create=True)
    for name in ("a", "b", "c"):
        sessions.save(DialogueState(name), create=True)
    assert sessions.ids() == [DEFAULT_DIALOGUE, "b", "c"]
    sessions.save(DialogueState("b", history=(Utterance("p", "hi"),)))
    sessions.save(DialogueState("d"), create=True)
    assert sessions.ids() == [DEFAULT_DIALOGUE, "b", "d"]
    sessions.delete("b")
    sessions.delete("never")
    assert sessions.ids() == [DEFAULT_DIALOGUE, "d"]
    with pytest.raises(ValueError, match="at least 1"):
        MemorySessions(0)
