"""Rays of a map world on grid lines and cell corners (review 13, degenerate-input lens).

A blocked cell of ``World(grid=...)`` is the closed square a box of the polygon
world is (the lidar kernels' doc: "a beam that only touches a blocked cell's
corner counts"), and ``World.raycast`` promises 0 on every ray from a point on a
blocked cell. The grid walk broke both where a ray met a grid line exactly:

* a beam along a grid line read the cell on one side or the other by the sign
  of ``sin(±pi)`` (1.2e-16): from (1.5, 1.0) along the face of a blocked cell,
  the angle pi read inf and -pi read 0.5 m, one beam written two ways;
* a beam entering the map from outside along a cell line read 0 (-0.0): the
  walk stepped to the crossing of the line it started on, "before" its entry;
* an origin on the top or right face of a blocked cell read inf on the rays
  pointing away (the bottom and left faces read 0);
* a beam through a corner missed a blocked cell touched there when rounding of
  its direction put the corner's two line crossings a hair apart, or when the
  walk left a large free square exactly at that corner.

Checked against the polygon world made of the same cells as boxes, on origins
and angles on the half-cell lattice (9 % of such beams disagreed before).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import box

from hypothesis_twins import slow_twin
from navkit.mapping import OccupancyGrid
from navkit.sim import Lidar, World


def _worlds(occupied: np.ndarray, res: float = 1.0,
            origin: tuple[float, float] = (0.0, 0.0)) -> tuple[World, World]:  # fmt: skip
    """The map world and the polygon world of the same cells as boxes."""
    grid = OccupancyGrid.from_occupancy(occupied, resolution=res, origin=(*origin, 0.0))
    ox, oy = origin
    boxes = [
        box(ox + c * res, oy + r * res, ox + (c + 1) * res, oy + (r + 1) * res)
        for r, c in np.argwhere(occupied)
    ]
    return World(grid=grid), World(boxes)


# One blocked cell, (0, 2): x in [2, 3], y in [0, 1].
_ONE = np.array([[0, 0, 1], [0, 0, 0]], dtype=bool)

# The same beam, pointing -x, written as (heading, angle) in five ways.
_MINUS_X = [(0.0, math.pi), (0.0, -math.pi), (math.pi, 0.0), (-math.pi, 0.0), (0.0, 3 * math.pi)]


@pytest.mark.parametrize(("heading", "angle"), _MINUS_X)
def test_a_beam_along_a_blocked_face_reads_the_same_however_written(
    heading: float, angle: float
) -> None:
    grid_world, boxes = _worlds(_ONE)
    # Along y = 1, the top face of the cell, from inside the map and from outside.
    for x, want in ((3.5, 0.5), (4.5, 1.5)):
        pose = (x, 1.0, heading)
        got = grid_world.raycast(pose, [angle], range_max=10.0)[0]
        assert got == boxes.raycast(pose, [angle], range_max=10.0)[0] == want
    # From (1.5, 1.0) the beam points away from the cell (-x): nothing.
    assert grid_world.raycast((1.5, 1.0, heading), [angle], range_max=10.0)[0] == math.inf


def test_a_beam_from_outside_along_a_cell_line_is_no_phantom_return() -> None:
    grid_world, _ = _worlds(_ONE)
    # sin(-pi) < 0 walked the beam into row 0 "before" it entered the map: -0.0.
    ranges = grid_world.raycast((4.5, 1.0, 0.0), [-math.pi, math.pi], range_max=10.0)
    assert ranges.tolist() == [1.5, 1.5]
    # Along y = 2, the map's top edge, nothing is blocked: no return at all.
    assert grid_world.raycast((4.5, 2.0, 0.0), [-math.pi, math.pi], range_max=10.0).tolist() == [
        math.inf, math.inf,
    ]  # fmt: skip


@pytest.mark.parametrize("point", [(2.5, 1.0), (3.0, 0.5), (3.0, 1.0), (2.0, 0.5), (2.5, 0.0)])
def test_an_origin_on_any_face_of_a_blocked_cell_reads_zero_on_every_ray(
    point: tuple[float, float],
) -> None:
    grid_world, boxes = _worlds(_ONE)
    angles = np.arange(8) * math.pi / 4
    got = grid_world.raycast((*point, 0.0), angles, range_max=10.0)
    assert got.tolist() == boxes.raycast((*point, 0.0), angles, range_max=10.0).tolist()
    assert got.tolist() == [0.0] * 8 and not np.signbit(got).any()


def test_a_beam_entering_the_map_through_a_corner_touches_that_cell() -> None:
    grid_world, boxes = _worlds(_ONE)
    # From (4, -1) at 135 degrees the beam meets the map only at its corner (3, 0).
    pose = (4.0, -1.0, 0.0)
    angle = 3 * math.pi / 4
    got = grid_world.raycast(pose, [angle], range_max=10.0)[0]
    assert got == pytest.approx(math.sqrt(2.0), abs=1e-12)
    assert boxes.raycast(pose, [angle], range_max=10.0)[0] == pytest.approx(got, abs=1e-12)


def test_a_corner_passed_to_rounding_touches_its_cells() -> None:
    """cos(-3pi/4) and sin(-3pi/4) differ in the last bit: the beam through the
    corner (16, 4) crossed its row line a hair first and missed cell (4, 15)."""
    occupied = np.zeros((20, 20), dtype=bool)
    occupied[4, 15] = True
    grid_world, boxes = _worlds(occupied)
    for heading, angle in ((-math.pi / 2, -math.pi / 4), (0.0, -3 * math.pi / 4)):
        got = grid_world.raycast((16.5, 4.5, heading), [angle], range_max=100.0)[0]
        assert got == pytest.approx(math.sqrt(0.5), abs=1e-12)
        assert boxes.raycast((16.5, 4.5, heading), [angle], range_max=100.0)[0] == pytest.approx(
            got, abs=1e-12
        )


def test_a_beam_leaving_a_large_free_square_at_a_corner_touches_the_cell_there() -> None:
    """The walk jumps across free squares; one left exactly at a corner skipped the
    cell beside the next one (here (41, 40), touched at its corner (41, 41))."""
    occupied = np.zeros((60, 60), dtype=bool)
    occupied[41, 40] = True
    grid_world, boxes = _worlds(occupied)
    got = grid_world.raycast((0.5, 0.5, 0.0), [math.pi / 4], range_max=200.0)[0]
    assert got == pytest.approx(40.5 * math.sqrt(2.0), abs=1e-9)
    assert boxes.raycast((0.5, 0.5, 0.0), [math.pi / 4], range_max=200.0)[0] == pytest.approx(
        got, abs=1e-9
    )


def test_a_full_circle_lidar_on_a_cell_line_sees_both_faces_alike() -> None:
    """The 360-beam scan of a robot level with two walls' faces, one each side.

    Its beam at -pi (behind) and at 0 (ahead) both run along a face: both read it.
    """
    occupied = np.zeros((4, 12), dtype=bool)
    occupied[1, 0:2] = True  # behind: top face y = 2, x in [0, 2]
    occupied[1, 10:12] = True  # ahead: the same face, x in [10, 12]
    grid_world, boxes = _worlds(occupied)
    lidar = Lidar(n_beams=360, noise=None, range_max=20.0)
    pose = (6.0, 2.0, 0.0)
    ranges = lidar.scan(grid_world, pose).ranges
    assert ranges[0] == ranges[180] == 4.0  # beams -pi and 0
    np.testing.assert_allclose(ranges, lidar.scan(boxes, pose).ranges, rtol=0.0, atol=1e-9)


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    shape=st.tuples(st.integers(1, 40), st.integers(1, 40)),
    density=st.sampled_from([0.005, 0.02, 0.1, 0.4]),
    res=st.sampled_from([1.0, 0.5]),
    origin=st.tuples(st.integers(-3, 3), st.integers(-3, 3)),
)
def test_rays_on_the_half_cell_lattice_match_the_cell_boxes(
    seed: int, shape: tuple[int, int], density: float, res: float, origin: tuple[int, int]
) -> None:
    rng = np.random.default_rng(seed)
    rows, cols = shape
    occupied = rng.random(shape) < density
    ox, oy = float(origin[0]), float(origin[1])
    grid_world, boxes = _worlds(occupied, res, (ox, oy))
    angles = np.arange(-8, 9) * math.pi / 4
    for _ in range(8):
        x = ox + int(rng.integers(-4, 2 * cols + 5)) * 0.5 * res
        y = oy + int(rng.integers(-4, 2 * rows + 5)) * 0.5 * res
        heading = float(
            rng.choice([0.0, math.pi, -math.pi, math.pi / 2, -math.pi / 2, 0.75 * math.pi])
        )
        got = grid_world.raycast((x, y, heading), angles, range_max=100.0)
        want = boxes.raycast((x, y, heading), angles, range_max=100.0)
        np.testing.assert_allclose(got, want, rtol=0.0, atol=1e-9, err_msg=f"{(x, y, heading)}")
        assert not np.signbit(got).any()


test_rays_on_the_half_cell_lattice_match_the_cell_boxes_thoroughly = slow_twin(
    test_rays_on_the_half_cell_lattice_match_the_cell_boxes, max_examples=400
)
