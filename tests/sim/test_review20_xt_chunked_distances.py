"""Cross-track distances in sub-quadratic time (review 20, XT): bit-identical to the plain loop.

``point_polyline_distances_chunked`` skips chunks of segments whose bounding box
is farther than the best distance so far (by more than rounding can reach); the
result must be the very floats the plain O(points x segments) loop computes.
The oracle is the plain kernel as it was at HEAD 33e58e0, copied here (so that
a later edit of the module's copy cannot move both sides at once), plus a NumPy
brute force for the values themselves.
"""

from __future__ import annotations

import math

import numba
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.sim._polyline_distance_kernels import (
    CHUNK,
    GROUP,
    SIMPLE_MAX_SEGMENTS,
    chunk_boxes,
    point_polyline_distances,
    point_polyline_distances_chunked,
)
from navkit.sim._trace import cross_track


@numba.njit(cache=False)
def _head_kernel(points: np.ndarray, path: np.ndarray, out: np.ndarray) -> None:
    # HEAD 33e58e0's point_polyline_distances, verbatim.
    k = path.shape[0]
    for i in range(points.shape[0]):
        px = points[i, 0]
        py = points[i, 1]
        best = math.hypot(px - path[0, 0], py - path[0, 1])
        for j in range(k - 1):
            ax = path[j, 0]
            ay = path[j, 1]
            ex = path[j + 1, 0] - ax
            ey = path[j + 1, 1] - ay
            wx = px - ax
            wy = py - ay
            ee = ex * ex + ey * ey
            t = 0.0
            if ee > 0.0:
                t = min(max((wx * ex + wy * ey) / ee, 0.0), 1.0)
            d = math.hypot(wx - t * ex, wy - t * ey)
            if d < best:
                best = d
        out[i] = best


def _head(points: np.ndarray, path: np.ndarray) -> np.ndarray:
    out = np.empty(points.shape[0])
    _head_kernel(np.ascontiguousarray(points), np.ascontiguousarray(path), out)
    return out


def _chunked(points: np.ndarray, path: np.ndarray) -> np.ndarray:
    out = np.full(points.shape[0], -1.0)
    point_polyline_distances_chunked(points, path, chunk_boxes(path), out)
    return out


def _numpy_oracle(points: np.ndarray, path: np.ndarray) -> np.ndarray:
    """Distance to the nearest segment (or the one vertex), vectorised."""
    best = np.hypot(points[:, 0] - path[0, 0], points[:, 1] - path[0, 1])
    a = path[:-1][None, :, :]
    e = (path[1:] - path[:-1])[None, :, :]
    if e.shape[1] == 0:
        return best
    w = points[:, None, :] - a
    ee = (e * e).sum(-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.where(ee > 0.0, np.clip((w * e).sum(-1) / np.where(ee > 0, ee, 1.0), 0, 1), 0.0)
    d = np.hypot(*(w - t[..., None] * e).transpose(2, 0, 1))
    return np.minimum(best, d.min(axis=1))


def _assert_identical(points: np.ndarray, path: np.ndarray) -> np.ndarray:
    points_before, path_before = points.copy(), path.copy()
    got = _chunked(points, path)
    expected = _head(points, path)
    assert np.array_equal(got, expected, equal_nan=True), (
        np.flatnonzero(got != expected)[:5], got[got != expected][:5],
        expected[got != expected][:5],
    )  # fmt: skip
    # The plain kernel in the module is still HEAD's.
    plain = np.empty(points.shape[0])
    point_polyline_distances(points, path, plain)
    assert np.array_equal(plain, expected, equal_nan=True)
    assert np.array_equal(points, points_before, equal_nan=True)
    assert np.array_equal(path, path_before, equal_nan=True)
    return got


@st.composite
def _case(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray]:
    seed = draw(st.integers(0, 2**32 - 1))
    k = draw(st.sampled_from([2, 3, CHUNK, CHUNK + 1, CHUNK + 2, 65, 66, 300,
                              CHUNK * GROUP + 1, CHUNK * GROUP + 7, 2500]))  # fmt: skip
    shape = draw(st.sampled_from(["walk", "zigzag", "dupes", "line", "uniform"]))
    scale = draw(st.sampled_from([1e-9, 1e-3, 1.0, 1e3]))
    offset = draw(st.sampled_from([0.0, 1e6, -3.5e6]))
    rng = np.random.default_rng(seed)
    if shape == "walk":
        path = np.cumsum(rng.normal(0.0, 1.0, (k, 2)), axis=0)
    elif shape == "zigzag":
        path = np.column_stack([np.arange(k) * 0.1, np.where(np.arange(k) % 2 == 0, 0.0, 5.0)])
    elif shape == "dupes":
        path = np.cumsum(rng.normal(0.0, 1.0, (k, 2)), axis=0)
        path[rng.integers(0, k, k // 2)] = path[0]  # repeated vertices, zero-length legs
        path = np.repeat(path, 2, axis=0)[:k]
    elif shape == "line":
        path = np.column_stack([np.linspace(0.0, 100.0, k), np.zeros(k)])
    else:
        path = rng.uniform(-50.0, 50.0, (k, 2))
    path = path * scale + offset
    n = draw(st.integers(1, 120))
    lo, hi = path.min(axis=0), path.max(axis=0)
    pad = (hi - lo) * 0.3 + scale
    points = rng.uniform(lo - pad, hi + pad, (n, 2))
    if draw(st.booleans()):  # a run along the path: points near consecutive vertices
        rows = np.sort(rng.integers(0, k, n))
        points = path[rows] + rng.normal(0.0, scale * 0.2, (n, 2))
    if draw(st.booleans()):  # some points exactly on vertices
        points[:: max(n // 4, 1)] = path[rng.integers(0, k, points[:: max(n // 4, 1)].shape[0])]
    return np.ascontiguousarray(points), np.ascontiguousarray(path)


@settings(max_examples=40, deadline=None)
@given(_case())
def test_chunked_equals_head_bit_for_bit(case: tuple[np.ndarray, np.ndarray]) -> None:
    points, path = case
    got = _assert_identical(points, path)
    span = float(np.abs(path).max()) + float(np.abs(points).max())
    np.testing.assert_allclose(got, _numpy_oracle(points, path), rtol=1e-9, atol=1e-12 * span)


test_chunked_equals_head_bit_for_bit_thoroughly = slow_twin(
    test_chunked_equals_head_bit_for_bit, max_examples=400
)


@pytest.mark.parametrize("k", [1, 2, 3, CHUNK, CHUNK + 1, 2 * CHUNK + 1])
def test_short_paths_and_one_vertex(k: int) -> None:
    rng = np.random.default_rng(k)
    path = rng.normal(0.0, 2.0, (k, 2))
    points = rng.normal(0.0, 3.0, (50, 2))
    got = _assert_identical(points, path)
    np.testing.assert_allclose(got, _numpy_oracle(points, path), rtol=1e-12, atol=1e-12)


def test_points_equidistant_to_many_segments() -> None:
    # A regular polygon around the origin: the centre is equidistant (up to
    # rounding) to every one of its 4000 edges; a comb of parallel teeth puts
    # points exactly halfway between two teeth in different chunks.
    angles = np.linspace(0.0, 2.0 * np.pi, 4001)
    circle = np.column_stack([np.cos(angles), np.sin(angles)]) * 7.0
    centre = np.array([[0.0, 0.0], [1e-9, -1e-9], [0.5, 0.25]])
    _assert_identical(centre, circle)
    teeth = []
    for x in range(200):
        teeth += [[float(x), 0.0], [float(x), 10.0], [x + 0.5, 10.0], [x + 0.5, 0.0]]
    comb = np.array(teeth)
    halfway = np.column_stack([np.arange(199) + 0.25, np.full(199, 5.0)])
    got = _assert_identical(halfway, comb)
    assert np.all(got == 0.25)


def test_tiny_distances_to_long_segments_far_from_the_origin() -> None:
    # Rounding in the segment distance is relative to the segment's length and
    # the point's offset, not to the distance: the skip slack must cover it.
    # Two long parallel legs 2e-9 m apart, in chunks far apart along the path,
    # 1e6 m from the origin; points between them.
    rng = np.random.default_rng(5)
    n_filler = 3 * CHUNK * GROUP
    out_leg = np.column_stack([np.linspace(1e6, 1e6 + 1e3, 2), np.full(2, 1e6)])
    filler = np.column_stack([np.full(n_filler, 1e6 + 1e3 + 5.0),
                              np.linspace(1e6, 1e6 + 500.0, n_filler)])  # fmt: skip
    back_leg = np.column_stack([np.linspace(1e6 + 1e3, 1e6, 2), np.full(2, 1e6 + 2e-9)])
    path = np.vstack([out_leg, filler, back_leg])
    x = rng.uniform(1e6, 1e6 + 1e3, 400)
    points = np.column_stack([x, 1e6 + rng.uniform(-1e-9, 3e-9, 400)])
    # Some exactly halfway between the legs (as far as the grid of floats allows).
    points[::3, 1] = 1e6 + 1e-9
    _assert_identical(points, path)
    _assert_identical(points[::-1].copy(), path[::-1].copy())


def test_nan_vertices_and_points_match_head() -> None:
    # Not reachable through Simulation (paths are checked finite), but the
    # kernel must not skip what the plain loop would have read.
    rng = np.random.default_rng(11)
    path = np.cumsum(rng.normal(0.0, 1.0, (3000, 2)), axis=0)
    path[[5, 700, 2999], 0] = np.nan
    path[1500, 1] = np.nan
    points = path[rng.integers(0, 3000, 300)] + rng.normal(0.0, 0.5, (300, 2))
    points[7] = np.nan
    _assert_identical(points, path)
    path[0] = np.nan
    assert np.all(np.isnan(_assert_identical(points, path)))


def test_chunk_boxes_hold_every_vertex_of_their_segments() -> None:
    rng = np.random.default_rng(3)
    for k in (2, CHUNK + 1, CHUNK * GROUP + 2, 5000):
        path = rng.normal(0.0, 10.0, (k, 2))
        boxes = chunk_boxes(path)
        nchunk = -(-(k - 1) // CHUNK)
        assert boxes.shape == (nchunk + -(-nchunk // GROUP), 5)
        for c in range(nchunk):
            seg = path[c * CHUNK : min(c * CHUNK + CHUNK, k - 1) + 1]
            assert np.array_equal(boxes[c, :2], seg.min(axis=0))
            assert np.array_equal(boxes[c, 2:4], seg.max(axis=0))
            g = nchunk + c // GROUP
            assert np.all(boxes[g, :2] <= boxes[c, :2]) and np.all(boxes[g, 2:4] >= boxes[c, 2:4])
        assert np.all(boxes[:, 4] >= 0.0)


@pytest.mark.parametrize("k", [2, SIMPLE_MAX_SEGMENTS + 1, SIMPLE_MAX_SEGMENTS + 2, 3000])
def test_cross_track_on_either_side_of_the_threshold(k: int) -> None:
    rng = np.random.default_rng(k)
    s = np.linspace(0.0, 50.0, k)
    path = np.column_stack([s, np.sin(s)])
    points = np.column_stack([np.linspace(-5.0, 55.0, 500), rng.normal(0.0, 1.0, 500)])
    got = cross_track(points, path)
    assert np.array_equal(got, _head(points, path))
    # Read-only and non-contiguous inputs give the same floats.
    view = np.asfortranarray(path)
    view.flags.writeable = False
    assert np.array_equal(cross_track(points[:, :], view), got)


def test_rounding_at_a_far_segments_end_is_not_skipped() -> None:
    # A point just past the end (0, 0) of a 1.4 km diagonal segment alone in its
    # chunk: the box's distance is the true distance to that end, but the
    # computed one rounds the long leg (fl(px - ax) - fl(bx - ax)), an error of
    # ~6e-14 m, 1e-4 of the 1e-9 m distance. Another segment, in the first
    # chunk, is 1e-7 closer. A relative margin alone (SCALE's prototype skipped
    # when box distance^2 > best^2 * (1 + 1e-9)) skipped the chunk and differed
    # from the plain loop on about half of these points.
    rng = np.random.default_rng(0)
    filler = [[5000.0, 100.0 + k] for k in range(CHUNK - 2)]
    for _ in range(100):
        d1, d2 = rng.uniform(0.5e-9, 1e-9, 2)
        y_a = -d2 - math.hypot(d1, d2) * (1.0 - 1e-7)
        path = np.array([[-1.0, y_a], [1.0, y_a], *filler, [1000.0, 1000.0], [0.0, 0.0]])
        assert path.shape[0] - 2 == CHUNK  # the diagonal is the first of its chunk
        _assert_identical(np.array([[-d1, -d2]]), path)
