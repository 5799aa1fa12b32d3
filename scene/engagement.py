"""Visual social engagement of people with the robot, in 2D (scene-compat §8).

The metric is hri_engagement 2.0.1's, with z = 0: mutual gaze (each party's gaze term from the
angle off its own axis) times a distance factor; each tick records +1 above the threshold and −1
below, and the mean of the last ``window`` samples drives the same five-level state machine.
The level is stored in the KB as ``<person> engagementLevel <level>`` (a functional property
minted in the ontology; ``engaging``, ``engaged``, ``disengaging``, ``disengaged`` are ORO's
EngagementLevel individuals; UNKNOWN is the absence of the fact).
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Iterable
from dataclasses import dataclass
from enum import IntEnum

from scene.scene import Entity


class Level(IntEnum):
    """hri_msgs/EngagementLevel constants."""

    UNKNOWN = 0
    DISENGAGED = 1
    ENGAGING = 2
    ENGAGED = 3
    DISENGAGING = 4

    @property
    def individual(self) -> str | None:
        """The ORO individual naming this level in the KB (None for UNKNOWN)."""
        return None if self is Level.UNKNOWN else self.name.lower()


@dataclass(frozen=True)
class EngagementConfig:
    max_distance: float = 4.0
    fov_degrees: float = 60.0  # half-angle of attention for person and robot
    threshold: float = 0.5
    window: int = 100  # 10 s at 10 Hz
    min_samples: int = 50


@dataclass(frozen=True)
class Transition:
    person: str
    before: Level
    after: Level


def gaze_term(forward: float, side: float, fov_degrees: float) -> float:
    """1 on the gaze axis, 0 at the edge of the field of view or behind (§8.1)."""
    if forward <= 0:
        return 0.0
    return max(0.0, 1.0 - abs(side) / (math.tan(math.radians(fov_degrees)) * forward))


def distance_factor(d: float, max_distance: float) -> float:
    """ln(max + 1 − d) / ln(max + 1): 1 at the robot, 0 at ``max_distance`` (§8.2)."""
    if d >= max_distance:
        return 0.0
    return math.log(max_distance + 1 - d) / math.log(max_distance + 1)


def engagement(person: Entity, config: EngagementConfig) -> float:
    """S for a person facing ``person.heading`` at (x, y) in the robot's frame; −1 when too far."""
    x, y = person.x, person.y
    d = math.hypot(x, y)
    if d > config.max_distance:
        return -1.0
    c, s = math.cos(person.heading), math.sin(person.heading)
    # The robot (at the origin) seen from the person's gaze frame.
    forward, side = -x * c - y * s, x * s - y * c
    person_to_robot = gaze_term(forward, side, config.fov_degrees)
    robot_to_person = gaze_term(x, y, config.fov_degrees)
    factor = distance_factor(d, config.max_distance) if x > 0 else 0.0
    return min(1.0, person_to_robot * robot_to_person * factor)


class _Track:
    __slots__ = ("level", "samples")

    def __init__(self, window: int) -> None:
        self.samples: deque[int] = deque(maxlen=window)
        self.level = Level.UNKNOWN


class EngagementTracker:
    """Per-person sample windows and levels; call ``observe`` once per tick (10 Hz upstream)."""

    def __init__(self, config: EngagementConfig | None = None) -> None:
        self.config = config or EngagementConfig()
        self._tracks: dict[str, _Track] = {}

    def level(self, person: str) -> Level:
        track = self._tracks.get(person)
        return track.level if track else Level.UNKNOWN

    def levels(self) -> dict[str, Level]:
        return {person: track.level for person, track in self._tracks.items()}

    def observe(self, people: Iterable[Entity]) -> list[Transition]:
        """Record one sample for each person present; forget the others (their level is lost)."""
        config = self.config
        changes: list[Transition] = []
        present: set[str] = set()
        for person in people:
            present.add(person.id)
            track = self._tracks.setdefault(person.id, _Track(config.window))
            track.samples.append(1 if engagement(person, config) > config.threshold else -1)
            after = _next_level(track, config)
            if after is not track.level:
                changes.append(Transition(person.id, track.level, after))
                track.level = after
        for gone in set(self._tracks) - present:
            before = self._tracks.pop(gone).level
            if before is not Level.UNKNOWN:
                changes.append(Transition(gone, before, Level.UNKNOWN))
        return changes


def _next_level(track: _Track, config: EngagementConfig) -> Level:
    """At most one transition per tick (§8.3)."""
    n = len(track.samples)
    level = track.level
    if level is Level.UNKNOWN:
        return Level.DISENGAGED if n >= config.min_samples else level
    m = sum(track.samples) / n
    if level is Level.DISENGAGED and m > -0.4:
        return Level.ENGAGING
    if level is Level.ENGAGING:
        if m < -0.6:
            return Level.DISENGAGED
        if m > 0.5:
            return Level.ENGAGED
    if level is Level.ENGAGED and m < 0.4:
        return Level.DISENGAGING
    if level is Level.DISENGAGING:
        if m > 0.6:
            return Level.ENGAGED
        if m < -0.5:
            return Level.DISENGAGED
    return level
