"""grid_to_msg_fields publishes a map's unknown pixels as -1 whatever its thresholds.

read_map gives unknown pixels log-odds 0 only when the YAML's thresholds class
p = 0.5 as unknown; otherwise they carry the middle of the unknown band. The
message used to publish those as that percentage (e.g. 25), which every
consumer (Nav2's static layer, map_server's own -1 convention) reads as known
space, while write_map's scale mode writes the same cells transparent.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import grid_to_msg_fields, read_map
from navkit.mapping.io._map_files import pgm_bytes


def _map_with_thresholds(folder: Path, image: Path, occupied: float, free: float) -> Path:
    yaml_path = folder / "map.yaml"
    yaml_path.write_text(
        yaml.safe_dump(
            {
                "image": str(image),
                "resolution": 0.05,
                "origin": [0.0, 0.0, 0.0],
                "negate": 0,
                "occupied_thresh": occupied,
                "free_thresh": free,
            }
        )
    )
    return yaml_path


def _check_unknown_published(grid: OccupancyGrid) -> None:
    data = grid_to_msg_fields(grid).data.reshape(grid.shape)
    unknown = grid.unknown()
    assert unknown.any()
    assert (data[unknown] == -1).all()
    # Known cells keep their percentages, and the message agrees with its trinary form.
    trinary = grid_to_msg_fields(grid, mode="trinary").data.reshape(grid.shape)
    np.testing.assert_array_equal(data == -1, trinary == -1)
    np.testing.assert_array_equal(data[grid.occupied()], 100)
    np.testing.assert_array_equal(data[grid.free()], 0)


def test_turtlebot3_map_with_band_below_one_half(shared_data: Path, tmp_path: Path) -> None:
    image = shared_data / "ros-map-server-maps" / "turtlebot3_world" / "map.pgm"
    # 205 (p = 0.196) stays unknown, 0.5 is occupied under these thresholds.
    grid = read_map(_map_with_thresholds(tmp_path, image, 0.4, 0.1))
    _check_unknown_published(grid)


@settings(max_examples=40, deadline=None)
@given(
    free=st.floats(0.01, 0.6),
    width=st.floats(0.05, 0.39),
    levels=st.lists(st.integers(0, 255), min_size=6, max_size=6),
)
def test_unknown_pixels_become_minus_one(
    tmp_path_factory: pytest.TempPathFactory, free: float, width: float, levels: list[int]
) -> None:
    occupied = free + width
    pixel_p = 1.0 - np.arange(256) / 255.0
    band = np.flatnonzero((free <= pixel_p) & (pixel_p <= occupied))
    levels[0] = int(band[len(band) // 2])  # at least one unknown pixel
    folder = tmp_path_factory.mktemp("m")
    image = folder / "map.pgm"
    image.write_bytes(pgm_bytes(np.array(levels, dtype=np.uint8).reshape(2, 3)))
    grid = read_map(_map_with_thresholds(folder, image, occupied, free))
    _check_unknown_published(grid)
