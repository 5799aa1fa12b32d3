"""The ROS parameters of situated's node (``/chatbot``): declared with defaults, which a parameters
YAML (``--ros-args --params-file FILE``) or ``-p name:=value`` overrides, as on any ROS node.

Values are checked when the node starts (a bad one stops it, saying which and why); an integer is
taken where seconds are expected (``-p turn_deadline:=3``). Only ``default_locale`` changes while the
node runs (``ros2 param set``, or the ``~/set_default_locale`` action); the others are read at start,
and a change is refused with the reason.

>>> check(NodeParameters(turn_deadline=3, default_locale="fr-fr"))
NodeParameters(turn_deadline=3.0, voices=False, default_locale='fr_FR', diagnostics_period=1.0)
>>> refusal("turn_deadline", 2.0)
"parameter 'turn_deadline' is read when the node starts: restart it with -p turn_deadline:=..."
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any

from dialogue.locales import LocaleError, normalise_locale

#: The chatbot's answer must reach a dialogue manager that waits 5 s (dialogue_manager's
#: chatbot_response_timeout), polite fallback included: the turn's own deadline is below it.
DEFAULT_TURN_DEADLINE = 4.0
#: What changes while the node runs.
LIVE = frozenset({"default_locale"})


class ParameterError(ValueError):
    """A parameter value the node cannot use; the message names it and says why."""


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


def _seconds(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not 0 < value <= 600:
        raise ParameterError(f"parameter {name!r} must be a number of seconds above 0 (at most 600), "
                             f"not {value!r}")
    return float(value)


def locale_value(value: Any) -> str:
    """A default locale: '' (none) or ll_CC."""
    if not isinstance(value, str):
        raise ParameterError(f"parameter 'default_locale' must be a string (ll_CC, or empty), not {value!r}")
    try:
        return normalise_locale(value) if value.strip() else ""
    except LocaleError as exc:
        raise ParameterError(f"parameter 'default_locale': {exc}") from None


def check(parameters: NodeParameters) -> NodeParameters:
    """The parameters as the node uses them; ParameterError for one it cannot use."""
    if not isinstance(parameters.voices, bool):
        raise ParameterError(f"parameter 'voices' must be true or false, not {parameters.voices!r}")
    return NodeParameters(turn_deadline=_seconds("turn_deadline", parameters.turn_deadline),
                          voices=parameters.voices, default_locale=locale_value(parameters.default_locale),
                          diagnostics_period=_seconds("diagnostics_period", parameters.diagnostics_period))


def refusal(name: str, value: Any) -> str | None:
    """Why a change of ``name`` to ``value`` while the node runs is refused; None: it is taken."""
    if name not in LIVE:
        return f"parameter {name!r} is read when the node starts: restart it with -p {name}:=..."
    try:
        locale_value(value)
    except ParameterError as exc:
        return str(exc)
    return None


def declare(node: Any, defaults: NodeParameters | None = None) -> NodeParameters:
    """Declare every parameter on ``node`` with ``defaults`` and read back what the node was given
    (checked). Typed dynamically: ``turn_deadline:=3`` is three seconds, not a type error."""
    from rcl_interfaces.msg import ParameterDescriptor  # a ROS message: only once a node starts

    base = defaults if defaults is not None else NodeParameters()
    values: dict[str, Any] = {}
    for spec in fields(NodeParameters):
        descriptor = ParameterDescriptor(dynamic_typing=True,
                                         read_only=spec.name not in LIVE)
        values[spec.name] = node.declare_parameter(spec.name, getattr(base, spec.name), descriptor).value
    return check(NodeParameters(**values))
