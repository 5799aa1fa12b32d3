"""2D geometry of the scene: axis-aligned boxes and field-of-view sectors (scene-compat §4–5).

Frame: the robot's ``base_link`` (REP-103), metres; x forward, y to the robot's left, angles
counter-clockwise from +x in radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

_EPS = 1e-9


@dataclass(frozen=True, slots=True)
class Box:
    """An axis-aligned rectangle given by its bounds."""

    xmin: float
    ymin: float
    xmax: float
    ymax: float

    @classmethod
    def around(cls, x: float, y: float, width: float, depth: float, heading: float = 0.0) -> Box:
        """The axis-aligned bounds of a ``width`` × ``depth`` rectangle centred on (x, y) and
        turned by ``heading`` (width along the heading)."""
        c, s = abs(math.cos(heading)), abs(math.sin(heading))
        half_x = (width * c + depth * s) / 2
        half_y = (width * s + depth * c) / 2
        return cls(x - half_x, y - half_y, x + half_x, y + half_y)

    @property
    def centre(self) -> tuple[float, float]:
        return ((self.xmin + self.xmax) / 2, (self.ymin + self.ymax) / 2)

    @property
    def area(self) -> float:
        return max(0.0, self.xmax - self.xmin) * max(0.0, self.ymax - self.ymin)

    def corners(self) -> tuple[tuple[float, float], ...]:
        xmin, ymin, xmax, ymax = self.xmin, self.ymin, self.xmax, self.ymax
        return ((xmin, ymin), (xmax, ymin), (xmax, ymax), (xmin, ymax))

    def contains(self, x: float, y: float) -> bool:
        return self.xmin <= x <= self.xmax and self.ymin <= y <= self.ymax

    def overlaps(self, other: Box) -> bool:
        """True when the intersection has an area (touching edges do not count, as in Qt)."""
        return (
            self.xmin < other.xmax and other.xmin < self.xmax
            and self.ymin < other.ymax and other.ymin < self.ymax
        )

    def overlap_area(self, other: Box) -> float:
        w = min(self.xmax, other.xmax) - max(self.xmin, other.xmin)
        h = min(self.ymax, other.ymax) - max(self.ymin, other.ymin)
        return max(0.0, w) * max(0.0, h)

    def edges(self) -> tuple[tuple[tuple[float, float], tuple[float, float]], ...]:
        a, b, c, d = self.corners()
        return ((a, b), (b, c), (c, d), (d, a))


@dataclass(frozen=True, slots=True)
class Sector:
    """A field of view: the disc sector of ``radius`` around ``heading`` ± ``half_angle``."""

    x: float
    y: float
    heading: float
    half_angle: float
    radius: float

    def contains(self, px: float, py: float) -> bool:
        dx, dy = px - self.x, py - self.y
        dist = math.hypot(dx, dy)
        if dist > self.radius + _EPS:
            return False
        if dist < _EPS or self.half_angle >= math.pi:
            return True
        return abs(_angle_diff(math.atan2(dy, dx), self.heading)) <= self.half_angle + _EPS

    def intersects(self, box: Box) -> bool:
        """True if the sector and the box share a point (partial overlap is enough, §4)."""
        nx = min(max(self.x, box.xmin), box.xmax)
        ny = min(max(self.y, box.ymin), box.ymax)
        if (nx - self.x) ** 2 + (ny - self.y) ** 2 > (self.radius + _EPS) ** 2:
            return False  # the box's nearest point is out of range
        if box.contains(self.x, self.y):
            return True
        if any(self.contains(cx, cy) for cx, cy in box.corners()):
            return True
        edges = box.edges()
        if self.half_angle < math.pi:
            for side in (-1, 1):
                angle = self.heading + side * self.half_angle
                end = (self.x + self.radius * math.cos(angle), self.y + self.radius * math.sin(angle))
                if any(_segments_cross((self.x, self.y), end, a, b) for a, b in edges):
                    return True
        return any(self._arc_meets(a, b) for a, b in edges)

    def _arc_meets(self, a: tuple[float, float], b: tuple[float, float]) -> bool:
        # Points of segment ab at distance radius from the apex, then the angular test.
        (ax, ay), (bx, by) = a, b
        dx, dy = bx - ax, by - ay
        fx, fy = ax - self.x, ay - self.y
        qa = dx * dx + dy * dy
        qb = 2 * (fx * dx + fy * dy)
        qc = fx * fx + fy * fy - self.radius * self.radius
        disc = qb * qb - 4 * qa * qc
        if qa < _EPS or disc < 0:
            return False
        root = math.sqrt(disc)
        for t in ((-qb - root) / (2 * qa), (-qb + root) / (2 * qa)):
            if -_EPS <= t <= 1 + _EPS and self.contains(ax + t * dx, ay + t * dy):
                return True
        return False


def _angle_diff(a: float, b: float) -> float:
    return (a - b + math.pi) % (2 * math.pi) - math.pi


def _segments_cross(
    p1: tuple[float, float], p2: tuple[float, float], q1: tuple[float, float], q2: tuple[float, float]
) -> bool:
    def orient(a: tuple[float, float], b: tuple[float, float], c: tuple[float, float]) -> float:
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])

    d1, d2 = orient(q1, q2, p1), orient(q1, q2, p2)
    d3, d4 = orient(p1, p2, q1), orient(p1, p2, q2)
    if ((d1 > 0 > d2) or (d1 < 0 < d2)) and ((d3 > 0 > d4) or (d3 < 0 < d4)):
        return True

    def on_segment(a: tuple[float, float], b: tuple[float, float], c: tuple[float, float]) -> bool:
        return min(a[0], b[0]) - _EPS <= c[0] <= max(a[0], b[0]) + _EPS and \
            min(a[1], b[1]) - _EPS <= c[1] <= max(a[1], b[1]) + _EPS

    return (
        (abs(d1) < _EPS and on_segment(q1, q2, p1)) or (abs(d2) < _EPS and on_segment(q1, q2, p2))
        or (abs(d3) < _EPS and on_segment(p1, p2, q1)) or (abs(d4) < _EPS and on_segment(p1, p2, q2))
    )
