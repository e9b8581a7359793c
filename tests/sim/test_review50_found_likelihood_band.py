"""diff-astar's scan matcher reads its field up to the map's edge (review 50, FOUND2).

``match_scan`` (the kernel of the scenario's ``LikelihoodField`` localiser) left
out every point between the edge cells' centres and the map's edge: a wall drawn
in the edge cells' outer halves was invisible, and a map one cell wide matched
nothing (the pose stayed at the prior). The edge cells' bilinear patch now
extends over that outer half cell; points beyond the edge are still left out.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.sim.scenarios._diff_astar_kernels import match_scan

_RES = 0.1
_WALL_X = 3.97  # inside the last column's outer half: its centre is 3.95, the edge 4.0


def _field(rows: int, cols: int = 40) -> np.ndarray:
    """Signed distance (m) at the cell centres to a wall ``x = _WALL_X`` (free for x < wall)."""
    centres_x = (np.arange(cols) + 0.5) * _RES
    return np.ascontiguousarray(np.tile(_WALL_X - centres_x, (rows, 1)))


def _match(
    values: np.ndarray, xs: np.ndarray, ys: np.ndarray, prior: tuple[float, ...]
) -> np.ndarray:
    out = np.zeros(3)
    match_scan(
        np.ascontiguousarray(xs), np.ascontiguousarray(ys), np.full(xs.shape, 1e-4), values,
        0.0, 0.0, 1.0, 0.0, _RES, 0.5, prior[0], prior[1], prior[2], 1e-6, 1e-6, 20, out,
    )  # fmt: skip
    return out


@pytest.mark.parametrize("truth_x", [1.0, 1.2, 0.63])
@pytest.mark.parametrize("error", [0.012, -0.015, 0.02])
def test_a_wall_in_the_edge_cells_outer_half_pulls_the_scan(truth_x: float, error: float) -> None:
    # Points on the wall seen from (truth_x, 2.0, 0): all in the band [3.95, 4.0) once
    # moved by the guess's error. The field is linear in x there, so the match is exact.
    ys = np.linspace(-1.0, 1.0, 21)
    xs = np.full(ys.shape, _WALL_X - truth_x)
    guess = (truth_x + error, 2.0, 0.0)
    assert 3.95 <= _WALL_X + error < 4.0
    out = _match(_field(40), xs, ys, guess)
    assert out[0] == pytest.approx(truth_x, abs=1e-6)
    assert out[1] == pytest.approx(2.0, abs=1e-6)
    assert out[2] == pytest.approx(0.0, abs=1e-6)


@pytest.mark.parametrize("y", [0.0, 0.01, 0.05, 0.099])
def test_a_map_one_cell_high_is_matched(y: float) -> None:
    # One row: every point lies in the row's outer halves (row coordinate in [-0.5, 0.5)).
    xs = np.array([2.97, 2.97, 2.97])
    guess = (1.012, y, 0.0)
    out = _match(_field(1), xs, np.zeros(3), guess)
    assert out[0] == pytest.approx(1.0, abs=1e-6)


def test_points_beyond_the_edge_are_left_out() -> None:
    # The wall seen 0.06 m farther: the points land beyond the edge (x >= 4.0), no pull.
    ys = np.linspace(-1.0, 1.0, 21)
    xs = np.full(ys.shape, 3.03)
    guess = (1.0, 2.0, 0.0)
    out = _match(_field(40), xs, ys, guess)
    assert out.tolist() == [1.0, 2.0, 0.0]


def test_inside_the_map_the_interpolation_is_unchanged() -> None:
    # A wall at 2.03 m: the points stay between centres; the match is the exact one.
    values = np.ascontiguousarray(_field(40) - (_WALL_X - 2.03))
    ys = np.linspace(-1.0, 1.0, 21)
    out = _match(values, np.full(ys.shape, 1.03), ys, (1.011, 2.0, 0.0))
    assert out[0] == pytest.approx(1.0, abs=1e-6)
