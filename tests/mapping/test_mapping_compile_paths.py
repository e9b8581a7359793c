"""Paths that keep the mapping kernels cheap to compile give the kernels' answers.

* one point: ``OccupancyGrid.world_to_cell`` / ``contains`` compute it in
  Python (no kernel compiled), bit for bit as ``world_to_cell_kernel``;
* the ray casting's scratch buffer: its prior contents never matter;
* ``correlative_search`` (scratch allocated in NumPy) equals its kernel;
* one compiled signature per kernel over the public entry points.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from kernel_signatures import compiled_signatures
from navkit._shared.jit import jit_disabled
from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, OccupancyGrid, integrate_scan
from navkit.mapping._grid_kernels import (
    world_to_cell_entry,
    world_to_continuous_kernel,
)
from navkit.mapping._raycast_kernels import integrate_beams
from navkit.mapping._scan_matcher_kernels import (
    correlative_search,
    correlative_search_kernel,
)

coords = st.floats(-1e9, 1e9, allow_nan=False) | st.floats(-1e3, 1e3)


@settings(max_examples=25, deadline=None)
@given(
    px=coords,
    py=coords,
    x=st.floats(-1e3, 1e3),
    y=st.floats(-1e3, 1e3),
    yaw=st.floats(-math.pi, math.pi),
    res=st.floats(1e-3, 10.0),
)
def test_one_point_in_python_equals_the_kernel(
    px: float, py: float, x: float, y: float, yaw: float, res: float
) -> None:
    grid = OccupancyGrid.empty(width=3.0, height=2.0, resolution=res, origin=Pose2D(x, y, yaw))
    o = grid.origin
    pts = np.array([[px, py]])
    cells = np.empty((1, 2), dtype=np.int64)
    # The entry: the kernel's one compiled version (the dispatcher would compile a second).
    world_to_cell_entry()(pts, o.x, o.y, o.theta, grid.resolution, cells)
    cont = np.empty((1, 2))
    world_to_continuous_kernel(pts, o.x, o.y, o.theta, grid.resolution, cont)
    one = grid.world_to_cell([px, py])
    assert one.dtype == np.int64 and one.shape == (2,)
    assert np.array_equal(one, cells[0])
    assert np.array_equal(grid.world_to_cell([[px, py]]), cells)
    assert np.array_equal(grid.world_to_cell((px, py), continuous=True), cont[0])
    rows, cols = grid.shape
    inside = bool(0 <= cells[0, 0] < rows and 0 <= cells[0, 1] < cols)
    assert bool(grid.contains((px, py))) is inside
    assert grid.contains([[px, py]]).tolist() == [inside]


test_one_point_in_python_equals_the_kernel_thoroughly = slow_twin(
    test_one_point_in_python_equals_the_kernel, max_examples=60
)


def _room_scan(n: int) -> LaserScan:
    angles = np.linspace(-math.pi, math.pi, n, endpoint=False)
    with np.errstate(divide="ignore"):
        ranges = np.minimum(3.0 / np.abs(np.cos(angles)), 2.0 / np.abs(np.sin(angles)))
    ranges[::7] = np.inf  # no echo: clears up to range_max
    return LaserScan(
        ranges, angle_min=-math.pi, angle_increment=2 * math.pi / n, range_min=0.1, range_max=2.5
    )


def test_ray_casting_scratch_contents_do_not_matter() -> None:
    scan = _room_scan(180)
    start = np.zeros((60, 80), dtype=np.float32)
    start[::5, ::3] = 0.3
    out = []
    for fill, exact in [(0, False), (255, False), (1, True), (2, True)]:
        logodds = start.copy()
        scratch = np.full(logodds.size + 17, fill, dtype=np.uint8)
        n = integrate_beams(
            logodds, -4.0, -3.0, 0.1, 0.1, 0.2, -0.1, 0.4, scan.ranges, scan.angle_min,
            scan.angle_increment, scan.range_min, scan.range_max, 0.85, -0.4, -2.0, 3.5, exact,
            scratch,
        )  # fmt: skip
        out.append((n, logodds))
    assert out[0][0] == out[1][0] and np.array_equal(out[0][1], out[1][1])
    assert out[2][0] == out[3][0] and np.array_equal(out[2][1], out[3][1])
    # And the public function (its own scratch) agrees.
    for exact, (n, expected) in [(False, out[0]), (True, out[2])]:
        grid = OccupancyGrid(start.copy(), resolution=0.1, origin=(-4.0, -3.0, 0.1))
        got = integrate_scan(
            grid, scan, (0.2, -0.1, 0.4), hit=0.85, miss=-0.4, clamp=(-2.0, 3.5), exact=exact
        )
        assert got == n
        assert np.array_equal(grid.logodds, expected)


def test_correlative_search_equals_its_kernel() -> None:
    rng = np.random.default_rng(5)
    logodds = rng.normal(0.0, 2.0, (40, 50)).astype(np.float32)
    points = rng.uniform(-1.5, 1.5, (30, 2))
    pose_a = np.array([2.0, 1.5, 0.2])
    pose_b = pose_a.copy()
    cost_a = correlative_search(
        logodds, 0.0, 0.0, 0.0, 0.1, points, pose_a, 2, 0.1, 3, 0.05, 0.5, 0.5
    )
    scratch = np.full((2, 30), np.nan)
    cost_b = correlative_search_kernel(
        logodds, 0.0, 0.0, 0.0, 0.1, points, pose_b, 2, 0.1, 3, 0.05, 0.5, 0.5, scratch
    )
    assert cost_a == cost_b
    assert np.array_equal(pose_a, pose_b)


#: The public entry points of the mapping kernels, each way that could pick another
#: type set (the exact ray casting, the matcher, both mapper updates, many points
#: as an array and as a list).
_PUBLIC_CALLS = """
import math
import numpy as np
from navkit.mapping import LaserScan, OccupancyGrid, ScanMapper, ScanMatcher, integrate_scan
angles = np.linspace(-math.pi, math.pi, 90, endpoint=False)
with np.errstate(divide="ignore"):
    ranges = np.minimum(3.0 / np.abs(np.cos(angles)), 2.0 / np.abs(np.sin(angles)))
ranges[::7] = np.inf
scan = LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / 90,
                 range_min=0.1, range_max=2.5)
room = OccupancyGrid.empty(width=8.0, height=6.0, resolution=0.1, origin=(-4.0, -3.0, 0.0))
integrate_scan(room, scan, (0.0, 0.0, 0.0))
integrate_scan(room, scan, (0.1, 0.0, 0.0), exact=True)
ScanMatcher().match(room, scan, (0.05, -0.05, 0.02))
mapper = ScanMapper(resolution=0.1)
mapper.update(scan)
mapper.update(scan, odometry=(0.5, 0.0, 0.95))
room.world_to_cell(np.array([[0.1, 0.2], [0.3, 0.4]]))
room.world_to_cell([[0.1, 0.2], [0.3, 0.4]])  # the general way
"""


# Compiled signatures are what is counted: with the JIT disabled the kernels are
# plain functions, with none.
@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: plain functions")
def test_one_signature_per_mapping_kernel() -> None:
    # In a fresh process: this one's kernels keep the signatures of every earlier
    # test's direct calls (a writable ``ranges`` passed to integrate_beams, say),
    # which ran before this test under another order or split of the suite (xdist).
    compiled = compiled_signatures(
        _PUBLIC_CALLS,
        [f"navkit.mapping.{name}" for name in (
            "_raycast_kernels", "_scan_matcher_kernels", "_grid_kernels"
        )],
    )  # fmt: skip
    for kernel in (
        "_raycast_kernels.integrate_beams",
        "_scan_matcher_kernels.accumulate",
        "_scan_matcher_kernels.match_level",
        "_scan_matcher_kernels.correlative_search_kernel",
        "_grid_kernels.world_to_cell_kernel",
    ):
        assert len(compiled.get(kernel, [])) == 1, (kernel, compiled)
