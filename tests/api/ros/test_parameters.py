"""The node's parameters: checked when the node starts, only default_locale changes while it runs."""

from __future__ import annotations

import pytest

from api.ros.parameters import DEFAULT_TURN_DEADLINE, NodeParameters, ParameterError, check, refusal


def test_the_turn_deadline_is_below_a_5_s_dialogue_manager_by_default() -> None:
    assert NodeParameters().turn_deadline == DEFAULT_TURN_DEADLINE < 5.0


def test_values_are_checked_and_normalised() -> None:
    assert check(NodeParameters(turn_deadline=2, diagnostics_period=1, default_locale="en-gb")) == \
        NodeParameters(turn_deadline=2.0, diagnostics_period=1.0, default_locale="en_GB")
    for bad, why in ((NodeParameters(turn_deadline=0), "'turn_deadline' must be a number of seconds above 0"),
                     (NodeParameters(turn_deadline=True), "'turn_deadline' must be a number"),
                     (NodeParameters(diagnostics_period=-1), "'diagnostics_period' must be a number"),
                     (NodeParameters(default_locale="klingon please"), "not a language tag"),
                     (NodeParameters(voices="yes"), "'voices' must be true or false")):  # type: ignore[arg-type]
        with pytest.raises(ParameterError, match=why):
            check(bad)


def test_only_the_default_locale_changes_while_the_node_runs() -> None:
    assert refusal("default_locale", "fr_FR") is None and refusal("default_locale", "") is None
    assert "not a language tag" in (refusal("default_locale", "nonsense words") or "")
    assert "read when the node starts" in (refusal("turn_deadline", 2.0) or "")
