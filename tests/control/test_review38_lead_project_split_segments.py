"""The trackers' closest-point search is the same however a path's segments are split (review 38).

``Polyline.project`` walks the path and stops at the first vertex past
``s_free`` that is more than ``detour`` farther from the robot than the closest
point so far. Tested at vertices only, a segment straddling ``s_free`` was
tested at its end alone: split into collinear pieces, a piece's end just past
``s_free`` stopped the search where the whole segment went on to a nearer later
pass (and a vertex exactly at ``s_free`` was not tested). The default suite's
hypothesis run found it (review 8's ``test_collinear_points_change_nothing``:
``FollowTheCarrot`` turned -0.084 rad/s on a path and +0.122 rad/s on the same
path split in two). The point at ``s_free`` is now tested too. Fails on the code before.
"""

from __future__ import annotations

import itertools

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st

from navkit.control._path_following import Polyline

_XY = st.floats(-3.0, 3.0)
_PATHS = st.lists(st.tuples(_XY, _XY), min_size=2, max_size=6)


def _split(path: np.ndarray, parts: int) -> np.ndarray:
    dense = [path[0]]
    for start, end in itertools.pairwise(path):
        dense.extend(start + (end - start) * (k / parts) for k in range(1, parts + 1))
    return np.array(dense)


@settings(max_examples=400, deadline=None)
@given(_PATHS, _XY, _XY, st.floats(0.0, 1.0), st.floats(0.0, 1.0), st.sampled_from([0.25, 0.5]),
       st.integers(2, 4))  # fmt: skip
@example([(2.25, 1.0), (3.0, 1.0), (2.5, 0.0)], 0.7098615282142294, 0.07952399856232392,
         0.0, 0.8 / 1.868033988749895, 0.25, 2)  # fmt: skip
# s_free on a vertex: the point there is tested (a return along the same line).
@example([(-3.0, 0.0), (0.0, 0.0), (-3.0, 0.0)], -2.0, 0.0, 0.1875, 0.5, 0.25, 2)
def test_splitting_segments_changes_no_closest_point(
    points: list[tuple[float, float]], x: float, y: float, start: float, free: float,
    detour: float, parts: int,
) -> None:  # fmt: skip
    path = np.array(points)
    seg = np.hypot(*np.diff(path, axis=0).T)
    if np.any(seg < 1e-3):
        return  # duplicate points are dropped by Polyline; near-duplicates round apart
    whole, split = Polyline(path), Polyline(_split(path, parts))
    length = whole.length
    s_from = start * length
    s_free = free * length
    s, d = whole.project(x, y, s_from, length, detour, s_free)
    s2, d2 = split.project(x, y, s_from, length, detour, s_free)
    # Split vertices are off the line by an ulp and arc lengths sum differently; a
    # tie between two passes (equal distances) may still go either way.
    assert abs(d - d2) <= 1e-9
    if abs(s - s2) > 1e-9:
        other = whole.project(x, y, s2 - 1e-12, s2 + 1e-12)[1]
        assert abs(other - d) <= 1e-9, (s, s2, d, d2)


def test_the_point_at_s_free_is_tested_as_a_vertex_is() -> None:
    # Leaving the robot from s = 0.75 (vertex (3, 1), before s_free = 0.8) and coming
    # back to (2.5, 0), nearer than the start: the path led 0.68 m farther than the
    # start's 1.79 m at s_free, so the search stops there and keeps the start.
    pts = np.array([[2.25, 1.0], [3.0, 1.0], [2.5, 0.0]])
    line = Polyline(pts)
    s, d = line.project(0.7098615282142294, 0.07952399856232392, 0.0, line.length, 0.25, 0.8)
    assert s == 0.0
    assert abs(d - float(np.hypot(2.25 - 0.7098615282142294, 1.0 - 0.07952399856232392))) < 1e-12
    # Without the detour (or with s_free past the far vertex) the end is nearer.
    s_all, _ = line.project(0.7098615282142294, 0.07952399856232392, 0.0, line.length)
    assert s_all == line.length
