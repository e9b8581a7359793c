"""Review 31 (scaling): the World's edge index grows linearly with its primitives.

The index's cells were sized by the obstacles' area alone, so long edges stacked
in a small area were each filed in O(sqrt(n)) cells: one box given 10,000 times
took 0.9 s to index (O(n^1.5) entries) and 50,000 copies 39 s before the index
was refused as too large. The cells are now at least as large as the
primitives' summed extent allows for 32 entries each. Counted, not timed; the
queries' answers do not depend on the cell size (compared bit for bit).

``World.collides`` tested a point against every solid circle in a Python loop
(0.5 µs per circle, 4.3 ms a query at 8000): only the circles whose bounding
square holds the point are tested now (23 µs at 8000).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from shapely.geometry import LineString, box

import navkit.sim._world as world_module
from navkit.sim import Circle, World


def _entries_per_primitive(world: World) -> float:
    primitives = world.segments.shape[0] + world.circles.shape[0]
    return world._cell_items.shape[0] / primitives


def test_one_box_repeated_fills_a_bounded_number_of_entries() -> None:
    # 4000 edges stacked on one square: the area-sized grid was 90 cells wide,
    # and each edge was filed in 91 of them (364,000 entries).
    world = World([box(5.0, 5.0, 6.0, 6.0)] * 1000)
    assert world.segments.shape[0] == 4000
    assert _entries_per_primitive(world) <= 66.0  # 91 before


def test_entries_per_primitive_do_not_grow_with_the_copies() -> None:
    small = _entries_per_primitive(World([box(0.0, 0.0, 1.0, 1.0)] * 250))
    large = _entries_per_primitive(World([box(0.0, 0.0, 1.0, 1.0)] * 4000))
    assert large <= small * 1.25


def test_a_spread_out_world_keeps_its_index() -> None:
    # Short edges over a wide area: the area sizes the cells, as before.
    walls = [box(x, y, x + 0.5, y + 0.5) for x in range(0, 40, 2) for y in range(0, 40, 2)]
    world = World(walls)
    cell = np.sqrt(world_module._CELLS_PER_PRIMITIVE * world.segments.shape[0])
    assert world._index[3] == pytest.approx(cell, abs=1.0)  # columns of a square area


@pytest.mark.parametrize("entries", [32.0, 4.0, 1.0])  # 32: the default
def test_answers_do_not_depend_on_the_cell_size(
    monkeypatch: pytest.MonkeyPatch, entries: float
) -> None:
    rng = np.random.default_rng(31)
    obstacles = [
        *[box(5.0, 5.0, 6.0, 6.0)] * 2000,
        *[LineString(4.0 + rng.random((2, 2)) * 3.0) for _ in range(60)],
        *[Circle(tuple(4.0 + rng.random(2) * 3.0), 0.2, solid=bool(k % 2)) for k in range(20)],
        box(4.0, 4.0, 7.0, 7.0).exterior,
    ]
    # The cells as sized before: by the area alone.
    monkeypatch.setattr(world_module, "_ENTRIES_PER_PRIMITIVE", np.inf)
    reference = World(obstacles)
    monkeypatch.setattr(world_module, "_ENTRIES_PER_PRIMITIVE", entries)
    other = World(obstacles)
    assert other._index[2] > reference._index[2]  # larger cells
    angles = np.linspace(-np.pi, np.pi, 91)
    for k in range(60):
        pose = (*(3.5 + rng.random(2) * 4.0), float(rng.uniform(-3.0, 3.0)))
        if k % 6 == 0:  # on an edge or a corner of the boxes
            pose = (5.0 + (k % 4) * 0.5, 6.0, 0.0)
        assert np.array_equal(
            reference.raycast(pose, angles, range_max=30.0),
            other.raycast(pose, angles, range_max=30.0),
        )
        assert reference.clearance(0.3, pose) == other.clearance(0.3, pose)
        assert reference.collides(0.3, pose) == other.collides(0.3, pose)


class _CountingMath:
    """The ``math`` module as :mod:`navkit.sim._world` sees it, counting ``hypot`` calls."""

    def __init__(self) -> None:
        self.hypot_calls = 0

    def __getattr__(self, name: str) -> object:
        return getattr(math, name)

    def hypot(self, *coordinates: float) -> float:
        self.hypot_calls += 1
        return math.hypot(*coordinates)


def test_collides_tests_only_the_solid_circles_near_the_point(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # 2000 solid circles of radius 0.05 m on a 0.3 m lattice. The inside test
    # looped over all of them in Python for every query (0.5 µs each, 4 ms at 8000).
    world = World([Circle((i % 50 * 0.3, i // 50 * 0.3), 0.05) for i in range(2000)])
    counter = _CountingMath()
    monkeypatch.setattr(world_module, "math", counter)
    assert world.collides(0.001, (3.0, 3.0, 0.0))  # inside the circle at (3.0, 3.0)
    assert not world.collides(0.001, (3.15, 3.15, 0.0))  # between four circles
    assert counter.hypot_calls <= 2
    # Inside and outside by a millimetre, the point test deciding (the footprint
    # touches no boundary).
    footprint = [[0.0, 0.0], [-1e-7, 1e-7], [-1e-7, -1e-7]]
    assert world.collides(footprint, (3.049, 3.0, 0.0))
    assert not world.collides(footprint, (3.051, 3.0, 0.0))
    assert counter.hypot_calls <= 4
