"""What a role's state says of its dialogue: open, or over with results and, called off, an error."""

from __future__ import annotations

from dialogue.sessions.rolestate import CALLED_OFF, Progress


def test_only_a_dialogue_called_off_has_an_error() -> None:
    assert (Progress().over, Progress().error_msg) == (False, "")
    assert (Progress("done", '{"a": 1}').over, Progress("done", '{"a": 1}').error_msg) == (True, "")
    called_off = Progress("cancelled", '{"a": 1}')
    assert called_off.over and called_off.error_msg == CALLED_OFF == "the person called the dialogue off"
