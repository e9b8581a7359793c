"""Read-only points compile no second ``world_to_continuous_kernel`` (review 32, latency).

``OccupancyGrid.world_to_cell(points, continuous=True)`` on two or more points
passed a read-only array (a ROS message's buffer, ``np.frombuffer``, a memory
map) to the kernel as it was: numba compiled a ``readonly array`` version of it,
0.14 s (6 ms from the disk cache) inside whichever call first got such points,
say in a control loop. Read-only points are copied to a writable array first.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from navkit.mapping import OccupancyGrid
from navkit.mapping._grid_kernels import world_to_continuous_kernel

#: The dispatcher (typed as the plain function it compiles).
_KERNEL: Any = world_to_continuous_kernel


def _read_only(points: np.ndarray) -> np.ndarray:
    out = points.copy()
    out.flags.writeable = False
    return out


def test_read_only_points_compile_no_new_signature() -> None:
    grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.5, origin=(0.1, -0.2, 0.3))
    points = np.array([[0.6, 0.1], [1.3, -0.4], [0.0, 0.0]])
    plain = grid.world_to_cell(points, continuous=True)  # the usual spelling first
    before = len(_KERNEL.signatures)
    frozen = _read_only(points)
    got = grid.world_to_cell(frozen, continuous=True)
    assert len(_KERNEL.signatures) == before
    np.testing.assert_array_equal(got, plain)


def test_read_only_points_give_the_same_cells_and_stay_read_only() -> None:
    grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.5, origin=(0.1, -0.2, 0.3))
    points = np.array([[0.6, 0.1], [1.3, -0.4], [0.0, 0.0]])
    frozen = _read_only(points)
    got = grid.world_to_cell(frozen, continuous=True)
    np.testing.assert_array_equal(got, grid.world_to_cell(points, continuous=True))
    assert got.flags.writeable
    assert not frozen.flags.writeable
    np.testing.assert_array_equal(frozen, points)
