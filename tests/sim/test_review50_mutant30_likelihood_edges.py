"""Review 50 (MUTANT30): diff-astar's matcher reads the field up to its low edges too.

``match_scan`` extends the edge cells' bilinear patch over the map's outer
half cell (review 50, FOUND2): a point between the first row's (or column's)
centre and the map's edge interpolates from cells 0 and 1, its cell index
clamped up from -1 to 0; one beyond the last centre from the last two cells.
The suite checked the last column only: mutants without the clamp up (cell
-1, which numba reads as the last row or column, wrapping around) or without
the last row's clamp down (a row past the array) survived. A wall in the
outer half of the first or last row, or of the first column, pulls the scan
onto it, exactly as at the last column.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.sim.scenarios._diff_astar_kernels import match_scan

_RES = 0.1
_N = 40
#: Walls inside the first cells' outer half (their centre 0.05 m, the edge 0) and the
#: last cells' (centre 3.95 m, edge 4.0 m).
_LOW = 0.03
_HIGH = 3.97


def _field(axis: int, wall: float) -> np.ndarray:
    """Signed distance (m) at the cell centres to a wall ``x = wall`` (``axis`` 1) or
    ``y = wall`` (``axis`` 0), free on the map's side of it."""
    centres = (np.arange(_N) + 0.5) * _RES
    side = 1.0 if wall < 1.0 else -1.0
    grid = np.tile(side * (centres - wall), (_N, 1))
    return np.ascontiguousarray(grid if axis == 1 else grid.T)


def _match(
    values: np.ndarray, xs: np.ndarray, ys: np.ndarray, prior: tuple[float, ...]
) -> np.ndarray:
    out = np.zeros(3)
    match_scan(
        np.ascontiguousarray(xs), np.ascontiguousarray(ys), np.full(xs.shape, 1e-4), values,
        0.0, 0.0, 1.0, 0.0, _RES, 0.5, prior[0], prior[1], prior[2], 1e-6, 1e-6, 20, out,
    )  # fmt: skip
    return out


@pytest.mark.parametrize("truth", [1.0, 1.2, 0.63])
@pytest.mark.parametrize("error", [0.012, -0.015, -0.018])
@pytest.mark.parametrize(
    ("axis", "wall"),
    [(1, _LOW), (0, _LOW), (0, _HIGH)],
    ids=["first-column", "first-row", "last-row"],
)
def test_a_wall_in_the_edge_cells_outer_half_pulls_the_scan(
    axis: int, wall: float, truth: float, error: float
) -> None:
    # Points on the wall seen from ``truth`` m away (on the map's side): all in the
    # edge cells' outer half once moved by the guess's error. The field is linear
    # there: the match is exact.
    side = 1.0 if wall < 1.0 else -1.0
    robot = wall + side * truth
    delta = side * error  # the guess's error
    assert 0.0 <= wall + delta < 0.05 or 3.95 <= wall + delta < 4.0
    along = np.linspace(-1.0, 1.0, 21)
    across = np.full(along.shape, wall - robot)
    if axis == 1:
        out = _match(_field(1, wall), across, along, (robot + delta, 2.0, 0.0))
        want = (robot, 2.0)
    else:
        # The robot facing +x: a point ``d`` to its left is ``d`` up in the world.
        out = _match(_field(0, wall), along, across, (2.0, robot + delta, 0.0))
        want = (2.0, robot)
    assert out[0] == pytest.approx(want[0], abs=1e-6)
    assert out[1] == pytest.approx(want[1], abs=1e-6)
    assert out[2] == pytest.approx(0.0, abs=1e-6)
