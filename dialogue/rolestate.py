"""What a role's saved state says about its dialogue (`Progress`): still open, or over, with results.

A dialogue of the default role is open until someone ends it; an ask dialogue is over once its form
is filled (`done`) or the person called it off (`cancelled`). Who waits for the end of a dialogue
(the ROS Dialogue action's goal) reads it here, whatever the role.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

Status = Literal["open", "done", "cancelled"]


@dataclass(frozen=True)
class Progress:
    """`status`, and the role's results so far: a JSON object string (the ask role: the fields obtained)."""

    status: Status = "open"
    results: str = "{}"

    @property
    def over(self) -> bool:
        return self.status != "open"
