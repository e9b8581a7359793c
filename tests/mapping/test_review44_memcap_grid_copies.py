"""Grid constructors keep the log-odds array they make, not a copy of it (review 44).

``OccupancyGrid.empty``, ``from_occupancy`` and ``from_probabilities`` (and so
``rasterize_polygons`` and ``grid_from_msg``) made a new float32 array and
handed it to the constructor, which copied it: 8 bytes a cell at the peak for
a 4-byte grid, 2 GiB for ``empty`` at ``OccupancyGrid.MAX_CELLS`` (2**28
cells), whose documented size is 1 GiB. A subclass's constructor that passes
another array still has it copied, and a caller's array is never kept.
"""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest
import shapely
from numpy.typing import ArrayLike

from memory_peak import peak_bytes
from navkit.mapping import OccupancyGrid, rasterize_polygons
from navkit.mapping.io import grid_from_msg, grid_to_msg_fields
from subprocess_probe import probe_outcome

ROWS, COLS = 1000, 1200
CELLS = ROWS * COLS
SLACK = 1 << 20  # a few small arrays and Python objects, far below a cell's 4 bytes


def _per_cell(peak: int) -> float:
    return peak / CELLS


def test_empty_allocates_the_grid_once() -> None:
    peak, grid = peak_bytes(
        lambda: OccupancyGrid.empty(width=COLS * 0.05, height=ROWS * 0.05, resolution=0.05)
    )
    assert grid.shape == (ROWS, COLS)
    assert not grid.logodds.any()
    assert peak < 4 * CELLS + SLACK, f"{_per_cell(peak):.2f} bytes a cell"  # was 8


def test_from_occupancy_allocates_the_grid_once() -> None:
    occupied = np.zeros((ROWS, COLS), dtype=bool)
    occupied[::7, ::3] = True
    unknown = np.zeros_like(occupied)
    unknown[1::7] = True
    peak, grid = peak_bytes(
        lambda: OccupancyGrid.from_occupancy(occupied, resolution=0.1, unknown=unknown)
    )
    assert np.array_equal(grid.occupied(), occupied)
    assert np.array_equal(grid.unknown(), unknown)
    # The grid (4) and the masks' overlap check (1).
    assert peak < 5 * CELLS + SLACK, f"{_per_cell(peak):.2f} bytes a cell"  # was 8


def test_from_probabilities_allocates_the_grid_and_a_block() -> None:
    p = np.random.default_rng(4).random((ROWS, COLS))
    peak, grid = peak_bytes(lambda: OccupancyGrid.from_probabilities(p, resolution=0.1))
    # A row block of float64 temporaries (1 MiB) beside the grid.
    assert peak < 4 * CELLS + 2 * SLACK, f"{_per_cell(peak):.2f} bytes a cell"  # was 8
    q = np.clip(p, 0.001, 0.999)
    assert np.array_equal(grid.logodds, np.log(q / (1.0 - q)).astype(np.float32))


def test_rasterize_polygons_allocates_the_mask_and_the_grid() -> None:
    square = shapely.box(10.0, 10.0, 30.0, 20.0)
    peak, grid = peak_bytes(
        lambda: rasterize_polygons(
            square, bounds=(0.0, 0.0, COLS * 0.05, ROWS * 0.05), resolution=0.05
        )
    )
    assert grid.shape == (ROWS, COLS)
    # Edges on cell boundaries occupy the cells on both sides: columns 199..600, rows 199..400.
    assert grid.occupied().sum() == 402 * 202
    assert peak < 5 * CELLS + SLACK, f"{_per_cell(peak):.2f} bytes a cell"  # was 9


def test_grid_from_msg_allocates_the_grid_and_the_table_indices() -> None:
    source = OccupancyGrid.from_probabilities(
        np.random.default_rng(5).random((ROWS, COLS)), resolution=0.05
    )
    fields = grid_to_msg_fields(source)
    position = SimpleNamespace(x=0.0, y=0.0, z=0.0)
    orientation = SimpleNamespace(x=0.0, y=0.0, z=0.0, w=1.0)
    info = SimpleNamespace(
        width=fields.width,
        height=fields.height,
        resolution=fields.resolution,
        origin=SimpleNamespace(position=position, orientation=orientation),
    )
    msg = SimpleNamespace(info=info, data=np.asarray(fields.data, dtype=np.int8))
    peak, grid = peak_bytes(lambda: grid_from_msg(msg))
    assert grid.shape == (ROWS, COLS)
    percent = np.asarray(fields.data).reshape(ROWS, COLS)
    p = np.where(percent < 0, 0.5, percent / 100.0)
    assert np.array_equal(grid.logodds, OccupancyGrid.from_probabilities(p, resolution=1.0).logodds)
    # The grid (4) and the look-up's int8 indices (1).
    assert peak < 5 * CELLS + SLACK, f"{_per_cell(peak):.2f} bytes a cell"  # was 8


def test_a_grid_keeps_only_an_array_no_one_else_holds() -> None:
    mine = np.zeros((3, 4), dtype=np.float32)
    grid = OccupancyGrid(mine, resolution=1.0)
    mine[0, 0] = 5.0  # the caller's array, copied
    assert grid.logodds[0, 0] == 0.0
    for made in (
        OccupancyGrid.empty(width=4.0, height=3.0, resolution=1.0),
        OccupancyGrid.from_occupancy(np.eye(3, dtype=bool), resolution=1.0),
        OccupancyGrid.from_probabilities(np.full((3, 4), 0.2), resolution=1.0),
    ):
        owner = made.logodds.base
        assert isinstance(owner, np.ndarray) and owner.base is None  # the grid's own
        assert owner.flags.writeable and owner.dtype == np.float32


class _Scaled(OccupancyGrid):
    """A subclass whose constructor passes another array to OccupancyGrid's."""

    __slots__ = ("made_from",)

    def __init__(self, logodds: ArrayLike, **kwargs: Any) -> None:
        self.made_from = logodds
        super().__init__(np.asarray(logodds) * 2.0, **kwargs)


class _Keeping(OccupancyGrid):
    """A subclass that keeps the array its constructor was given."""

    __slots__ = ("made_from",)

    def __init__(self, logodds: ArrayLike, **kwargs: Any) -> None:
        self.made_from = logodds
        super().__init__(logodds, **kwargs)


def test_subclasses_are_built_by_their_own_constructors() -> None:
    scaled = _Scaled.from_occupancy(np.eye(2, dtype=bool), resolution=1.0)
    assert isinstance(scaled, _Scaled)
    assert np.array_equal(scaled.logodds, 2.0 * np.asarray(scaled.made_from))
    kept = _Keeping.empty(width=2.0, height=2.0, resolution=1.0)
    assert isinstance(kept, _Keeping) and kept.shape == (2, 2)
    # Made for the grid and handed to the subclass, which chose to keep it too.
    assert np.shares_memory(kept.logodds, kept.made_from)


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs Linux's /proc")
def test_the_largest_empty_grid_fits_one_and_a_half_gib() -> None:
    # 2**28 cells: the grid's own 1 GiB; the copy took another 1 GiB (MemoryError here).
    outcome = probe_outcome(
        """
import json, resource
from navkit.mapping import OccupancyGrid
OccupancyGrid.empty(width=2.0, height=2.0, resolution=1.0)
with open("/proc/self/status") as f:
    size = next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmSize"))
resource.setrlimit(resource.RLIMIT_AS, (size + (3 << 29), resource.RLIM_INFINITY))
grid = OccupancyGrid.empty(width=16384.0, height=16384.0, resolution=1.0)
print(json.dumps([*grid.shape, grid.logodds.nbytes]))
""",
        timeout=600,
    )
    assert outcome == [16384, 16384, 1 << 30]
