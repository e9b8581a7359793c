"""Users' map-value mistakes get a message that names the likely cause and the fix.

ROS ``nav_msgs/OccupancyGrid`` data (percent 0..100, -1 unknown) passed as
probabilities, and a map YAML whose thresholds are written as percent.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map, write_map


def test_ros_percent_data_as_probabilities_names_grid_from_msg() -> None:
    ros_data = np.array([[0.0, 100.0], [-1.0, 50.0]])
    with pytest.raises(ValueError, match="probabilities") as err:
        OccupancyGrid.from_probabilities(ros_data, resolution=0.05)
    text = str(err.value)
    assert "got [-1, 100]" in text
    assert "grid_from_msg" in text


def test_probabilities_far_outside_percent_get_no_ros_hint() -> None:
    with pytest.raises(ValueError, match="probabilities") as err:
        OccupancyGrid.from_probabilities(np.array([[0.0, 255.0]]), resolution=0.05)
    assert "got [0, 255]" in str(err.value)
    assert "ROS" not in str(err.value)


def test_percent_thresholds_in_a_map_yaml_are_named(tmp_path: Path) -> None:
    grid = OccupancyGrid.from_occupancy(np.eye(3, dtype=bool), resolution=0.1)
    yaml_path = tmp_path / "map.yaml"
    write_map(grid, yaml_path)
    text = yaml_path.read_text()
    text = text.replace("occupied_thresh: 0.65", "occupied_thresh: 65")
    text = text.replace("free_thresh: 0.196", "free_thresh: 19.6")
    assert "occupied_thresh: 65" in text  # the edit took
    yaml_path.write_text(text)
    with pytest.raises(ValueError, match="occupied_thresh") as err:
        read_map(yaml_path)
    assert "not percent" in str(err.value)


def test_swapped_thresholds_get_no_percent_hint(tmp_path: Path) -> None:
    grid = OccupancyGrid.from_occupancy(np.eye(3, dtype=bool), resolution=0.1)
    yaml_path = tmp_path / "map.yaml"
    write_map(grid, yaml_path)
    text = yaml_path.read_text().replace("occupied_thresh: 0.65", "occupied_thresh: 0.1")
    yaml_path.write_text(text)
    with pytest.raises(ValueError, match="occupied_thresh") as err:
        read_map(yaml_path)
    assert "percent" not in str(err.value)
