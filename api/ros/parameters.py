"""The ROS parameters of situated's node (``/chatbot``): declared with defaults, which a parameters
YAML (``--ros-args --params-file FILE``) or ``-p name:=value`` overrides, as on any ROS node."""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any

#: The chatbot's answer must reach a dialogue manager that waits 5 s (dialogue_manager's
#: chatbot_response_timeout), polite fallback included: the turn's own deadline is below it.
DEFAULT_TURN_DEADLINE = 4.0


@dataclass(frozen=True)
class NodeParameters:
    #: Seconds a dialogue turn over ROS may take; past it the reply is the polite fallback.
    turn_deadline: float = DEFAULT_TURN_DEADLINE
    #: Listen to /humans/voices/*/speech and answer on /say (the IROS22 bridge's behaviour).
    voices: bool = False
    #: The locale of dialogues that do not say theirs (ll_CC); empty: the service's default.
    default_locale: str = ""
    #: Seconds between two /diagnostics messages.
    diagnostics_period: float = 1.0


def declare(node: Any, defaults: NodeParameters | None = None) -> NodeParameters:
    """Declare every parameter on ``node`` with ``defaults`` and read back what the node was given."""
    base = defaults if defaults is not None else NodeParameters()
    values: dict[str, Any] = {}
    for spec in fields(NodeParameters):
        default = getattr(base, spec.name)
        values[spec.name] = node.declare_parameter(spec.name, default).value
    return NodeParameters(**values)
