"""A map whose resolution is a float32 is inflated as its decimal twin (review 52, PRECISION).

``nav_msgs/OccupancyGrid`` carries the resolution as a float32, and
:func:`~navkit.mapping.io.grid_from_msg` keeps it as given: a 0.05 m map arrives
at 0.05000000074505806 m. A robot radius of 0.15 m, 3 cells by intent, was then
2.99999996 cells, beyond the 1e-9 cell of slack that ``inflate``, ``cells_near``
and ``costmap`` give a radius: the map read from its topic was inflated one cell
less (5 cm of the robot's body) than the same map read from its YAML. A
resolution that is a float32 above the decimal it stands for (the shortest decimal
float32 rounds to it) now takes radii in cells of that decimal; float64
resolutions keep their 1e-9 cell of slack, no more (review 33).

The oracle is exact integer arithmetic: a radius of ``k`` cells reaches the cells
whose offsets satisfy ``dr² + dc² <= k²``.
"""

from __future__ import annotations

import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid, costmap
from navkit.mapping.io import grid_from_msg

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from centred_obstacle import centred_grid, disc

# Resolutions of real maps; the float32 of most lies above the decimal (0.05, 0.1,
# 0.2, 0.025), which is what put whole-cell radii short of their cells.
DECIMALS = [0.01, 0.02, 0.025, 0.03, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.5, 1.0]
N = 31  # grid side; the obstacle at its centre
C = N // 2


def _float32(value: float) -> float:
    return float(np.float32(value))


@pytest.mark.parametrize("decimal", DECIMALS)
def test_whole_cell_radii_reach_their_cells_at_float32_resolutions(decimal: float) -> None:
    short = []
    for resolution in (decimal, _float32(decimal)):
        grid = centred_grid(N, resolution)
        for k in range(1, C + 1):
            radius = k * decimal  # what a user writes: 0.15 for 3 cells of 0.05 m
            want = disc(N, k)
            got = grid.inflate(radius)
            if not np.array_equal(got, want):
                short.append((resolution, k, int(want.sum() - got.sum())))
            cells = grid.cells_near([grid.cell_to_world([C, C])], robot_radius=radius)
            mask = np.zeros((N, N), dtype=bool)
            mask[cells[:, 0], cells[:, 1]] = True
            np.testing.assert_array_equal(mask, got)
    assert short == []


@pytest.mark.parametrize("decimal", [0.05, 0.1, 0.2, 0.025])
def test_the_costmap_inscribes_the_same_cells_at_float32_resolutions(decimal: float) -> None:
    for k in (1, 2, 3, 4, 7):
        radius = k * decimal
        for resolution in (decimal, _float32(decimal)):
            cost = costmap(
                centred_grid(N, resolution), robot_radius=radius, inflation_radius=2 * radius
            )
            np.testing.assert_array_equal(cost >= 253, disc(N, k), err_msg=f"{resolution} {k}")


@pytest.mark.parametrize("decimal", DECIMALS)
def test_radii_short_of_a_cell_still_stop_short_of_it(decimal: float) -> None:
    # The slack is 2.4e-7 of the radius: a radius 1e-6 short of k cells leaves out
    # the cells exactly k cells away (dr² + dc² = k², e.g. (k, 0)).
    r, c = np.mgrid[0:N, 0:N]
    for resolution in (decimal, _float32(decimal)):
        grid = centred_grid(N, resolution)
        for k in range(1, C + 1):
            got = grid.inflate(k * resolution * (1.0 - 1e-6))
            np.testing.assert_array_equal(got, (r - C) ** 2 + (c - C) ** 2 < k * k)


def _message(occ: np.ndarray, resolution: float, origin: tuple[float, float]) -> object:
    """A ``nav_msgs/OccupancyGrid`` look-alike, its resolution a float32 as on the wire."""
    rows, cols = occ.shape
    ns = SimpleNamespace
    info = ns(
        resolution=_float32(resolution), width=cols, height=rows,
        origin=ns(position=ns(x=origin[0], y=origin[1], z=0.0),
                  orientation=ns(x=0.0, y=0.0, z=0.0, w=1.0)),
    )  # fmt: skip
    return ns(info=info, data=np.where(occ, 100, 0).astype(np.int8).ravel().tolist())


def test_a_map_from_its_topic_costs_as_the_map_from_its_yaml() -> None:
    rng = np.random.default_rng(52)
    occ = rng.random((60, 80)) < 0.02
    origin = (512340.0, 5412340.0)  # a UTM origin, as a map_server map may have
    yaml_map = OccupancyGrid.from_occupancy(occ, resolution=0.05, origin=(*origin, 0.0))
    topic_map = grid_from_msg(_message(occ, 0.05, origin))
    assert topic_map.resolution == 0.05000000074505806
    for radius in (0.05, 0.1, 0.15, 0.2, 0.3):
        np.testing.assert_array_equal(topic_map.inflate(radius), yaml_map.inflate(radius))
        np.testing.assert_array_equal(
            topic_map.traversal_costs(robot_radius=radius, inflation_radius=0.5),
            yaml_map.traversal_costs(robot_radius=radius, inflation_radius=0.5),
        )
