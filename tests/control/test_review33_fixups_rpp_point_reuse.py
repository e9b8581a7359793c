"""Review 33 (FIXUPS): ``RegulatedPurePursuit.step`` reuses the closest point it found.

Review 32's fold check called ``point_at(s)`` for the closest point (0.4 µs of
a 7 µs step) after ``project`` had found ``s``; one kernel now returns both
(``project_offset`` since review 37, which works on offsets from the robot for
translation invariance). ``project``'s own distance is measured to the foot of
the perpendicular, which may differ from ``point_at(s)`` in the last bits (it
is not used): these tests pin that the offset is ``offset_at(s)``'s bit for
bit, so that every command stays as it was.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.control._path_following import Polyline

_coord = st.floats(-1e3, 1e3, allow_nan=False)


@settings(max_examples=300, deadline=None)
@given(
    pts=st.lists(st.tuples(_coord, _coord), min_size=1, max_size=8),
    offset=st.sampled_from([0.0, 1e6, -3e8]),
    robot=st.tuples(_coord, _coord),
    window=st.tuples(st.floats(-1.0, 1e4), st.floats(-1.0, 1e4)),
    free=st.floats(0.0, 1e4),
    detour=st.sampled_from([0.25, math.inf]),
)
def test_project_offset_is_project_then_offset_at_bit_for_bit(
    pts: list[tuple[float, float]],
    offset: float,
    robot: tuple[float, float],
    window: tuple[float, float],
    free: float,
    detour: float,
) -> None:
    line = Polyline(np.array(pts) + offset)
    x, y = robot[0] + offset, robot[1] + offset
    s_from, s_to = min(window), max(window)
    s, dx, dy = line.project_offset(x, y, s_from, s_to, detour, free)
    s_ref, _ = line.project(x, y, s_from, s_to, detour, free)
    assert s == s_ref
    assert (dx, dy) == line.offset_at(s_ref, x, y)[:2]


def test_polyline_end_is_point_at_length() -> None:
    for pts in ([[0.0, 0.0]], [[0.1, 0.2], [0.3, 0.7], [1e6 + 0.1, -2.0]]):
        line = Polyline(np.array(pts))
        assert line.end == line.point_at(line.length) == tuple(pts[-1])
