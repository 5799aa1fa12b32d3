"""The engagement metric and its state machine (scene-compat §8.2–8.3)."""

from __future__ import annotations

import math

import pytest

from scene.engagement import (
    EngagementConfig,
    EngagementTracker,
    Level,
    distance_factor,
    engagement,
    gaze_term,
)
from scene.scene import Entity, Kind


def facing_robot(x: float, y: float, person: str = "p1") -> Entity:
    return Entity(person, Kind.PERSON, x=x, y=y, heading=math.atan2(-y, -x))


@pytest.mark.parametrize(("d", "f"), [(0.5, 0.935), (1, 0.861), (2, 0.683), (2.5, 0.569), (3, 0.431), (4, 0.0)])
def test_distance_factor_reference_values(d: float, f: float) -> None:
    assert distance_factor(d, 4.0) == pytest.approx(f, abs=1e-3)


@pytest.mark.parametrize(("angle", "g"), [(0, 1.0), (10, 0.90), (20, 0.79), (30, 0.67), (45, 0.42), (60, 0.0)])
def test_gaze_term_reference_values(angle: float, g: float) -> None:
    a = math.radians(angle)
    assert gaze_term(math.cos(a), math.sin(a), 60.0) == pytest.approx(g, abs=0.01)


def test_mutual_gaze_threshold_distance() -> None:
    # With perfect mutual gaze, S > 0.5 needs d < 5 - sqrt(5) ≈ 2.76 m.
    assert engagement(facing_robot(2.7, 0.0), EngagementConfig()) > 0.5
    assert engagement(facing_robot(2.8, 0.0), EngagementConfig()) < 0.5
    assert engagement(facing_robot(4.5, 0.0), EngagementConfig()) == -1.0
    turned_away = Entity("p1", Kind.PERSON, x=1.0, y=0.0, heading=0.0)
    assert engagement(turned_away, EngagementConfig()) == 0.0
    behind_robot = facing_robot(-1.0, 0.0)
    assert engagement(behind_robot, EngagementConfig()) == 0.0


def run(tracker: EngagementTracker, person: Entity, ticks: int) -> list[tuple[int, Level]]:
    changes = []
    for i in range(ticks):
        for change in tracker.observe([person]):
            changes.append((i + 1, change.after))
    return changes


def test_state_machine_timings_from_disengaged_and_engaged() -> None:
    tracker = EngagementTracker()
    near, away = facing_robot(1.0, 0.0), Entity("p1", Kind.PERSON, x=1.0, y=0.0, heading=0.0)
    assert run(tracker, away, 100) == [(50, Level.DISENGAGED)]
    # From a full window of -1: ENGAGING after ~31 engaged ticks, ENGAGED after ~76 (§8.3).
    changes = run(tracker, near, 100)
    assert [level for _, level in changes] == [Level.ENGAGING, Level.ENGAGED]
    assert 29 <= changes[0][0] <= 32 and 74 <= changes[1][0] <= 77
    run(tracker, near, 50)  # full window of +1
    changes = run(tracker, away, 100)
    assert [level for _, level in changes] == [Level.DISENGAGING, Level.DISENGAGED]
    assert 29 <= changes[0][0] <= 32 and 74 <= changes[1][0] <= 77


def test_unknown_until_fifty_samples_and_forgotten_when_gone() -> None:
    tracker = EngagementTracker()
    person = facing_robot(1.0, 0.2)
    assert run(tracker, person, 49) == []
    assert tracker.level("p1") is Level.UNKNOWN
    run(tracker, person, 1)
    assert tracker.level("p1") is Level.DISENGAGED
    changes = tracker.observe([])
    assert [(c.person, c.after) for c in changes] == [("p1", Level.UNKNOWN)]
    assert tracker.levels() == {}
