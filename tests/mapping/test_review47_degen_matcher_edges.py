"""Review 47 (degenerate input): scan matching at the map's edges.

The matcher's map value ``M`` (bilinear between cell centres) read 0 from the
edge cells' centres outwards, inside the map: ``M`` jumped from the edge cell's
probability to 0 at its centre, a wall drawn in the outer half of the edge
cells was invisible, and a map one cell wide was not matched at all. A room
mapped tight to its walls matched several times worse than the same map with a
margin of unknown cells (6 of 30 matches ``"degenerate"``, errors up to 8 cm at
5 cm cells). Now the cells beyond the edge count as unknown there (and, since
review 50, past the edge too): the tight map is the padded one.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping import LaserScan, OccupancyGrid, ScanMatcher
from navkit.mapping._scan_matcher_kernels import interpolate_batch

_RES = 0.05
_CELLS = 40
_BEAMS = 180


def _room(margin: int) -> OccupancyGrid:
    """A square room whose walls are its edge cells, with ``margin`` unknown cells around."""
    occupied = np.zeros((_CELLS, _CELLS), dtype=bool)
    occupied[[0, -1], :] = True
    occupied[:, [0, -1]] = True
    occupied = np.pad(occupied, margin)
    unknown = np.pad(np.zeros((_CELLS, _CELLS), dtype=bool), margin, constant_values=True)
    corner = -margin * _RES
    return OccupancyGrid.from_occupancy(
        occupied, resolution=_RES, origin=(corner, corner, 0.0), unknown=unknown
    )


def _scan(x: float, y: float, theta: float, inset: float) -> LaserScan:
    """A noise-free scan of the room's walls, ``inset`` cells inside the map's edge."""
    low, high = inset * _RES, (_CELLS - inset) * _RES
    angles = theta - math.pi + 2.0 * math.pi / _BEAMS * np.arange(_BEAMS)
    c, s = np.cos(angles), np.sin(angles)
    with np.errstate(divide="ignore", invalid="ignore"):
        tx = np.where(c > 0, (high - x) / c, np.where(c < 0, (low - x) / c, np.inf))
        ty = np.where(s > 0, (high - y) / s, np.where(s < 0, (low - y) / s, np.inf))
    return LaserScan(
        np.minimum(tx, ty),
        angle_min=-math.pi,
        angle_increment=2.0 * math.pi / _BEAMS,
        range_min=0.0,
        range_max=20.0,
    )


@pytest.mark.parametrize("inset", [0.3, 0.45])
def test_walls_in_the_edge_cells_outer_half_are_matched(inset: float) -> None:
    # The walls lie between the edge cells' centres and the map's edge (``inset``
    # cells inside it): a tight map matches them as the same map with a margin of
    # unknown cells does. (Guesses within 0.2 cell, so that no point leaves the
    # tight map, where M was 0 until review 50 and the padded map's was not; see
    # test_review50_found_matcher_beyond_edge.py for guesses that do.)
    rng = np.random.default_rng(4701)
    tight, padded = _room(0), _room(2)
    matcher = ScanMatcher()
    for _ in range(8):
        x, y, theta = rng.uniform(0.6, 1.4), rng.uniform(0.6, 1.4), rng.uniform(-3.0, 3.0)
        scan = _scan(x, y, theta, inset)
        guess = (x + rng.normal(0, 0.004), y + rng.normal(0, 0.004), theta + rng.normal(0, 0.004))
        found = matcher.match(tight, scan, guess)
        reference = matcher.match(padded, scan, guess)
        assert found.reason == reference.reason == "converged"
        # Within a tenth of a cell of the truth (the walls are drawn on whole
        # cells, so neither is exact), and where the padded map puts it.
        assert math.hypot(found.pose.x - x, found.pose.y - y) <= 0.1 * _RES
        assert abs(found.pose.theta - theta) <= 0.01
        assert math.hypot(found.pose.x - reference.pose.x, found.pose.y - reference.pose.y) <= (
            0.02 * _RES
        )
        assert found.score == pytest.approx(reference.score, abs=1e-3)


@settings(max_examples=60, deadline=None)
@given(
    values=st.lists(st.floats(-6.0, 6.0), min_size=12, max_size=12),
    eps=st.floats(0.0, 0.25),
    along=st.floats(0.0, 2.0),
    side=st.sampled_from(["top", "bottom", "left", "right"]),
)
def test_m_is_continuous_up_to_the_map_edge(
    values: list[float], eps: float, along: float, side: str
) -> None:
    # M at distance eps (in cells) inside the edge cells' centres tends to M on
    # those centres, the edge cell's own probability.
    logodds = np.array(values, dtype=np.float32).reshape(4, 3)
    on, near = {
        "top": ((3.0, along), (3.0 - eps, along)),
        "bottom": ((0.0, along), (0.0 + eps, along)),
        "left": ((min(along, 3.0), 0.0), (min(along, 3.0), eps)),
        "right": ((min(along, 3.0), 2.0), (min(along, 3.0), 2.0 - eps)),
    }[side]
    out = np.empty((2, 3))
    interpolate_batch(logodds, np.array([on, near]), out)
    p = 1.0 / (1.0 + np.exp(-logodds.astype(np.float64)))
    row, col = on
    r0, c0 = min(int(row), 2), min(int(col), 1)
    b, a = row - r0, col - c0
    expected = (1 - b) * ((1 - a) * p[r0, c0] + a * p[r0, c0 + 1]) + b * (
        (1 - a) * p[r0 + 1, c0] + a * p[r0 + 1, c0 + 1]
    )
    assert out[0, 0] == pytest.approx(expected, abs=1e-7)
    # |∂M| <= 1 per cell along each axis, so M moves at most 2 eps.
    assert abs(out[1, 0] - out[0, 0]) <= 2.0 * eps + 1e-7


@settings(max_examples=60, deadline=None)
@given(
    values=st.lists(st.floats(-6.0, 6.0), min_size=12, max_size=12),
    row=st.floats(-0.5, 3.5, exclude_max=True),
    col=st.floats(-0.5, 2.5, exclude_max=True),
)
def test_the_outer_half_cell_reads_the_map_padded_with_unknown_cells(
    values: list[float], row: float, col: float
) -> None:
    logodds = np.array(values, dtype=np.float32).reshape(4, 3)
    padded = np.pad(logodds, 1)  # log-odds 0: unknown
    out = np.empty((1, 3))
    reference = np.empty((1, 3))
    interpolate_batch(logodds, np.array([[row, col]]), out)
    interpolate_batch(padded, np.array([[row + 1.0, col + 1.0]]), reference)
    # The padded coordinates' rounding (one ulp of row + 1) moves M by as little.
    assert out[0, 0] == pytest.approx(reference[0, 0], rel=0.0, abs=1e-12)
    # The gradient too, away from the kinks on the cell centres' lines (where
    # that rounding may pick the other one-sided derivative).
    if min(abs(row - round(row)), abs(col - round(col))) > 1e-9:
        assert out[0, 1:] == pytest.approx(reference[0, 1:], rel=0.0, abs=1e-12)


def test_beyond_the_edge_m_is_unknown() -> None:
    # A cell past the edge cells' centres every neighbour is unknown: M = 1/2, no
    # gradient (zeros until review 50); NaN coordinates still read zeros.
    logodds = np.full((4, 3), 5.0, dtype=np.float32)
    coords = np.array([[4.0, 1.0], [-1.0000001, 1.0], [1.0, 3.0], [1.0, -1.6], [1e300, -1e300]])
    out = np.full((len(coords), 3), np.nan)
    interpolate_batch(logodds, coords, out)
    assert out.tolist() == [[0.5, 0.0, 0.0]] * len(coords)
    interpolate_batch(logodds, np.array([[np.nan, 1.0], [1.0, np.nan]]), out[:2])
    assert (out[:2] == 0.0).all()


def test_m_is_continuous_from_the_edge_cells_to_the_unknown_beyond() -> None:
    # Across the edge and a cell past the edge cells' centres M has no jump.
    logodds = np.full((4, 3), 5.0, dtype=np.float32)
    tiny = 1e-9
    coords = np.array(
        [[r, 1.3] for r in (3.5 - tiny, 3.5 + tiny, 4.0 - tiny, 4.0 + tiny)]
        + [[1.3, c] for c in (-0.5 - tiny, -0.5 + tiny, -1.0 - tiny, -1.0 + tiny)]
    )
    out = np.empty((len(coords), 3))
    interpolate_batch(logodds, coords, out)
    for k in range(0, len(coords), 2):
        assert abs(out[k, 0] - out[k + 1, 0]) <= 1e-8


def test_a_map_one_cell_high_has_its_cells_values() -> None:
    # One row of cells: every point on it is in its outer half cell; M on the
    # occupied cell's centre is that cell's probability (it was 0 on every point).
    occupied = np.zeros((1, 60), dtype=bool)
    occupied[0, 20] = True
    wall = OccupancyGrid.from_occupancy(occupied, resolution=_RES)
    out = np.empty((1, 3))
    interpolate_batch(wall.logodds, np.array([[0.0, 20.0]]), out)
    assert out[0, 0] == pytest.approx(wall.probability()[0, 20], abs=1e-7)
    assert out[0, 0] > 0.9
