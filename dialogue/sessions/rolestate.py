"""What a role's saved state says about its dialogue (`Progress`): still open, or over, with results.

A dialogue of the default role is open until someone ends it; an ask dialogue is over once its form
is filled (`done`) or the person called it off (`cancelled`, which the ROS Dialogue action's result
reports with `error_msg`). Who waits for the end of a dialogue reads it here, whatever the role: the
ROS Dialogue action's goal, and REST (`GET /dialogues/{id}`, and `DELETE`'s answer).

>>> Progress("cancelled", '{"age": 7}').error_msg
'the person called the dialogue off'
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

Status = Literal["open", "done", "cancelled"]
#: The error of a dialogue the person called off ("never mind"): what was asked is not all obtained.
CALLED_OFF = "the person called the dialogue off"


@dataclass(frozen=True)
class Progress:
    """`status`, and the role's results so far: a JSON object string (the ask role: the fields obtained)."""

    status: Status = "open"
    results: str = "{}"

    @property
    def over(self) -> bool:
        return self.status != "open"

    @property
    def error_msg(self) -> str:
        """Why the dialogue ended without its role done (chatbot_msgs Dialogue's `error_msg`), or ""."""
        return CALLED_OFF if self.status == "cancelled" else ""
