"""Field-of-view sectors and boxes: the geometry behind `sees`, `isIn` and `isOn`."""

from __future__ import annotations

import math

import pytest

from scene.geometry import Box, Sector

ROBOT_FOV = Sector(0.0, 0.0, 0.0, math.radians(60), 3.5)  # 120° aperture, 3.5 m: the simulator's


@pytest.mark.parametrize(
    ("box", "seen", "why"),
    [
        (Box.around(2.0, 0.0, 0.2, 0.2), True, "straight ahead"),
        (Box.around(3.45, 0.0, 0.2, 0.2), True, "near edge overlaps the range"),
        (Box.around(3.65, 0.0, 0.2, 0.2), False, "just beyond the range"),
        (Box.around(1.0, 2.1, 0.2, 0.2), False, "just outside the 60° half-angle"),
        (Box.around(1.0, 1.62, 0.2, 0.2), True, "corner just inside the 60° half-angle"),
        (Box.around(-1.0, 0.0, 0.2, 0.2), False, "behind"),
        (Box.around(0.0, 0.0, 0.2, 0.2), True, "the apex is inside the box"),
        (Box.around(1.0, 0.0, 10.0, 10.0), True, "a zone that contains the whole sector"),
        (Box.around(3.4, 0.0, 0.1, 4.0), True, "a long box crossing the arc only"),
        (Box.around(1.0, 3.0, 4.0, 0.2), True, "a wall-like box crossing a side edge, no corner inside"),
    ],
)
def test_sector_intersects_box(box: Box, seen: bool, why: str) -> None:
    assert ROBOT_FOV.intersects(box) is seen, why


def test_sector_rotates_with_heading() -> None:
    facing_left = Sector(0.0, 0.0, math.pi / 2, math.radians(60), 3.5)
    assert facing_left.intersects(Box.around(0.0, 2.0, 0.2, 0.2))
    assert not facing_left.intersects(Box.around(2.0, 0.0, 0.2, 0.2))


def test_boxes_overlap_only_with_area() -> None:
    a = Box(0, 0, 1, 1)
    assert a.overlaps(Box(0.5, 0.5, 2, 2))
    assert not a.overlaps(Box(1, 0, 2, 1))  # touching edges
    assert a.overlap_area(Box(0.5, 0.5, 2, 2)) == pytest.approx(0.25)


def test_rotated_box_bounds() -> None:
    box = Box.around(0, 0, 2.0, 1.0, heading=math.pi / 2)
    assert (box.xmax - box.xmin, box.ymax - box.ymin) == (pytest.approx(1.0), pytest.approx(2.0))
