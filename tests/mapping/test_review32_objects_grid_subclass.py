"""Every alternative constructor of OccupancyGrid builds the subclass it is called on (review 32).

OBJECTS: ``MyGrid.from_occupancy``, ``from_probabilities`` and ``empty`` gave
a ``MyGrid``, but ``MyGrid.from_polygons`` and ``MyGrid.load`` returned a
plain ``OccupancyGrid`` (they hand over to ``rasterize_polygons`` and
``read_map``), so a subclass's methods and ``__init__`` were lost on the two
commonest ways of making a map. Both now return the subclass, with the very
log-odds, resolution, origin and thresholds; on ``OccupancyGrid`` itself they
return the function's grid, as before.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from shapely.geometry import box

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map


class TaggedGrid(OccupancyGrid):
    """A user's grid: a tag set by its own constructor, and a method of its own."""

    def __init__(self, logodds: Any, **kwargs: Any) -> None:
        super().__init__(logodds, **kwargs)
        self.tag = "built by TaggedGrid"

    def walls(self) -> int:
        return int(self.occupied().sum())


def _same_grid(a: OccupancyGrid, b: OccupancyGrid) -> None:
    np.testing.assert_array_equal(a.logodds, b.logodds)
    assert a.logodds.dtype == b.logodds.dtype
    assert (a.resolution, a.origin) == (b.resolution, b.origin)
    assert (a.occupied_thresh, a.free_thresh) == (b.occupied_thresh, b.free_thresh)


def test_from_polygons_builds_the_subclass() -> None:
    kw: dict[str, Any] = {"bounds": (0, 0, 3, 1), "resolution": 0.5}
    grid = TaggedGrid.from_polygons(box(1.2, 0.2, 1.8, 0.8), **kw)
    assert type(grid) is TaggedGrid and grid.tag == "built by TaggedGrid"
    assert grid.walls() == 4
    _same_grid(grid, OccupancyGrid.from_polygons(box(1.2, 0.2, 1.8, 0.8), **kw))
    assert type(OccupancyGrid.from_polygons(box(1.2, 0.2, 1.8, 0.8), **kw)) is OccupancyGrid


def test_load_builds_the_subclass(tmp_path: Path) -> None:
    occupied = np.zeros((4, 6), dtype=bool)
    occupied[1, 2:5] = True
    unknown = np.zeros_like(occupied)
    unknown[3, 0] = True
    OccupancyGrid.from_occupancy(
        occupied, resolution=0.25, origin=(1.0, -2.0, 0.0), unknown=unknown
    ).save(tmp_path / "map.yaml")
    grid = TaggedGrid.load(tmp_path / "map.yaml")
    assert type(grid) is TaggedGrid and grid.tag == "built by TaggedGrid"
    assert grid.walls() == 3
    _same_grid(grid, read_map(tmp_path / "map.yaml"))
    assert type(OccupancyGrid.load(tmp_path / "map.yaml")) is OccupancyGrid


def test_the_other_constructors_already_did() -> None:
    mask = np.eye(3, dtype=bool)
    assert type(TaggedGrid.from_occupancy(mask, resolution=1.0)) is TaggedGrid
    assert type(TaggedGrid.from_probabilities(mask * 0.9, resolution=1.0)) is TaggedGrid
    assert type(TaggedGrid.empty(width=1.0, height=1.0, resolution=0.5)) is TaggedGrid
