"""Saving a received map: navkit's write_map against an oracle of map_saver (review 51).

map_saver (Nav2's ``map_io.cpp`` ``saveMapToFile``, ROS 1's ``map_saver.cpp``)
writes a ``nav_msgs/OccupancyGrid`` in trinary mode pixel by pixel from the
message's values: -1 (or anything outside 0..100) as 205, a value
``<= rint(100 * free_thresh)`` as 254, one ``>= rint(100 * occupied_thresh)``
as 0, the rest 205. map_server reads 254 back as free, 0 as occupied and 205
as unknown under the YAML's thresholds.
"""

from __future__ import annotations

import inspect
from pathlib import Path
from types import SimpleNamespace as NS

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import grid_from_msg, read_map, write_map

FREE, OCCUPIED, UNKNOWN = "free", "occupied", "unknown"
VALUES = np.arange(-1, 101)


def map_saver_classes(values: np.ndarray, free_thresh: float, occupied_thresh: float) -> list[str]:
    """The class map_server reads back from map_saver's trinary pixel of each value."""
    free_int = round(free_thresh * 100)  # std::rint, exact here (no .5 ties)
    occupied_int = round(occupied_thresh * 100)
    out = []
    for v in values.tolist():
        if v < 0 or v > 100:
            out.append(UNKNOWN)  # pixel 205
        elif v <= free_int:
            out.append(FREE)  # pixel 254
        elif v >= occupied_int:
            out.append(OCCUPIED)  # pixel 0
        else:
            out.append(UNKNOWN)  # pixel 205
    return out


def _message(values: np.ndarray) -> NS:
    origin = NS(position=NS(x=0.0, y=0.0, z=0.0), orientation=NS(x=0.0, y=0.0, z=0.0, w=1.0))
    info = NS(width=values.size, height=1, resolution=0.05, origin=origin)
    return NS(info=info, data=values.tolist())


def _saved_classes(grid: OccupancyGrid, folder: Path) -> list[str]:
    write_map(grid, folder / "map.yaml")
    again = read_map(folder / "map.yaml")
    occupied, free = again.occupied()[0], again.free()[0]
    return [OCCUPIED if o else FREE if f else UNKNOWN for o, f in zip(occupied, free, strict=True)]


def _differing(ours: list[str], theirs: list[str]) -> list[int]:
    return [int(v) for v, a, b in zip(VALUES, ours, theirs, strict=True) if a != b]


@pytest.mark.parametrize(
    ("free_thresh", "occupied_thresh", "differ"),
    [
        (0.25, 0.65, [20, 21, 22, 23, 24, 25, 65]),  # Nav2's map_saver defaults
        (0.196, 0.65, [20, 65]),  # the YAML defaults navkit's grids carry
    ],
)
def test_a_message_saves_differently_at_map_savers_thresholds(
    tmp_path: Path, free_thresh: float, occupied_thresh: float, differ: list[int]
) -> None:
    grid = grid_from_msg(_message(VALUES))
    ours = _saved_classes(grid, tmp_path)
    theirs = map_saver_classes(VALUES, free_thresh, occupied_thresh)
    assert _differing(ours, theirs) == differ
    # Only values between 0 and 100 differ: trinary messages save the same.
    trinary = [VALUES.tolist().index(v) for v in (-1, 0, 100)]
    assert [ours[i] for i in trinary] == [theirs[i] for i in trinary] == [UNKNOWN, FREE, OCCUPIED]


def test_thresholds_half_a_percent_inside_give_map_savers_classes(tmp_path: Path) -> None:
    # The recipe of write_map's Notes.
    grid = grid_from_msg(_message(VALUES))
    inside = OccupancyGrid(
        grid.logodds,
        resolution=grid.resolution,
        origin=grid.origin,
        occupied_thresh=0.645,
        free_thresh=0.255,
    )
    assert _saved_classes(inside, tmp_path) == map_saver_classes(VALUES, 0.25, 0.65)
    notes = inspect.getdoc(write_map) or ""
    assert "rint(100 * occupied_thresh)" in notes
    assert "occupied_thresh=0.645" in notes
