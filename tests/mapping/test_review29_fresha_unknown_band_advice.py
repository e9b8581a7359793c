"""write_map's advice for a band with no unknown grey level was not always enough (fixed).

Review 28 made the refusal say how to widen the band between ``free_thresh`` and
``occupied_thresh``: "the same cells with thresholds more than 1/255 apart". But
map_server's levels ``p = 1 - v / 255`` are rounded, and the widest gap between
two of them is 9.7e-17 wider than 1/255: thresholds just inside such a gap, more
than 1/255 apart, were refused with the same advice. The advice now names a
width that holds for every band (0.004; the widest gap is 0.0039215686274510775).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import _map_files, write_map


def _refusal(tmp_path: Path) -> str:
    # Every cell unknown (p = 0.5) in a band of 0.001 that holds no grey level.
    grid = OccupancyGrid(
        np.zeros((2, 2), dtype=np.float32), resolution=0.1, occupied_thresh=0.5005,
        free_thresh=0.4995,
    )  # fmt: skip
    with pytest.raises(ValueError, match="widen the band") as info:
        write_map(grid, tmp_path / "narrow.yaml")
    return str(info.value)


def _advised_width(message: str) -> float:
    found = re.search(r"at least ([0-9.]+) apart", message)
    if found is not None:
        return float(found.group(1))
    assert "more than 1/255 apart" in message, message
    return math.nextafter(1.0 / 255.0, 1.0)


def test_thresholds_as_far_apart_as_advised_can_be_written(tmp_path: Path) -> None:
    width = _advised_width(_refusal(tmp_path))
    levels = np.sort(_map_files._pixel_p(_map_files._GREY_LEVELS))
    widest = int(np.argmax(np.diff(levels)))
    free = math.nextafter(float(levels[widest]), 1.0)  # just inside the widest gap
    occupied = free + width
    assert occupied - free >= width
    middle = 0.5 * (free + occupied)
    grid = OccupancyGrid(
        np.full((2, 2), math.log(middle / (1.0 - middle)), dtype=np.float32),
        resolution=0.1, occupied_thresh=occupied, free_thresh=free,
    )  # fmt: skip
    assert grid.unknown().all()
    write_map(grid, tmp_path / "advised.yaml")  # refused before: no level in the band
