"""The narrow-band advice of write_map, followed literally (review 28, lead).

"widen the band between them" said what to do but not how, on a grid whose
thresholds are fixed when it is built: the message now says how.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map, write_map


def test_the_narrow_band_advice_rebuilds_a_grid_that_writes(tmp_path: object) -> None:
    grid = OccupancyGrid(np.zeros((2, 3)), resolution=0.1, occupied_thresh=0.5, free_thresh=0.499)
    path = f"{tmp_path}/m.yaml"
    with pytest.raises(ValueError, match="widen the band") as info:
        write_map(grid, path)
    message = str(info.value)
    assert "OccupancyGrid(grid.logodds, resolution=grid.resolution, origin=grid.origin" in message
    wider = OccupancyGrid(grid.logodds, resolution=grid.resolution, origin=grid.origin,
                          occupied_thresh=0.65, free_thresh=0.196)  # fmt: skip
    write_map(wider, path)
    back = read_map(path)
    assert back.unknown().all()  # p = 0.5 everywhere: unknown, as written
