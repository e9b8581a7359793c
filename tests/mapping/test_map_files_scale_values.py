"""Scale-mode map files keep in-between probabilities as closely as 8-bit grey allows."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map, write_map

pytest.importorskip("PIL")  # scale mode writes PNG with Pillow


@pytest.mark.parametrize(
    ("p", "occupied_thresh", "free_thresh"),
    [
        (0.6499, 0.65, 0.196),  # rounds to grey 89, which reads 0.651: occupied
        (0.1961, 0.65, 0.196),  # grey 205 reads 0.19608: no threshold crossed
        (0.75, 1.0, 0.75),  # rounds to grey 64, which reads 0.749: free
        (0.0, 1.0, 1e-80),  # clipped to 0.001, grey 255 would read free
    ],
)
def test_in_between_cells_keep_the_nearest_unknown_grey(
    tmp_path: Path, p: float, occupied_thresh: float, free_thresh: float
) -> None:
    # The issue: an in-between cell whose rounded grey crossed a threshold was
    # written as the middle of the unknown band (0.6499 came back as 0.42).
    grid = OccupancyGrid.from_probabilities(
        [[p, 0.5]], resolution=0.1, occupied_thresh=occupied_thresh, free_thresh=free_thresh
    )
    assert grid.unknown()[0, 0]
    write_map(grid, tmp_path / "m.yaml", mode="scale")
    back = read_map(tmp_path / "m.yaml")
    assert back.unknown()[0, 0]
    # Independently: map_server's reading 1 - v / 255 of every grey level v, the
    # ones it reads as unknown under these thresholds, and the nearest of them.
    readings = 1.0 - np.arange(256) / 255.0
    band = readings[(readings >= free_thresh) & (readings <= occupied_thresh)]
    want = grid.probability()[0, 0]
    nearest = band[np.argmin(np.abs(band - want))]
    assert back.probability()[0, 0] == pytest.approx(nearest, abs=1e-6)
