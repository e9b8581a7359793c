"""``from_probabilities``'s range error says what it got, and its ROS hint is apt (review 11).

* A value just above 1 (``1.0000001``) printed as ``got [0, 1]`` (``:g``): the
  range quoted looked valid.
* Any values in [-1, 100] got "this looks like ROS OccupancyGrid data ... divide
  by 100": log-odds (``[-0.8, 2.2]``) are not ROS data, and dividing them by 100
  gives a wrong map without an error. ROS data are whole numbers (int8), and
  with -1 (unknown) present, dividing by 100 is still refused: the hint's
  conversion now maps -1 to 0.5, which this test runs.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid


def test_a_value_just_above_one_is_quoted_exactly() -> None:
    with pytest.raises(ValueError, match="probabilities") as err:
        OccupancyGrid.from_probabilities([[0.0, 1.0000001]], resolution=0.1)
    assert "1.0000001" in str(err.value)


def test_log_odds_get_no_ros_hint() -> None:
    with pytest.raises(ValueError, match="probabilities") as err:
        OccupancyGrid.from_probabilities([[-0.8, 0.0, 2.2]], resolution=0.1)
    assert "ROS" not in str(err.value) and "100" not in str(err.value)


def test_the_ros_hint_conversion_reads_the_data() -> None:
    data = np.array([[-1, 0, 100], [100, 0, -1]])
    with pytest.raises(ValueError, match="ROS") as err:
        OccupancyGrid.from_probabilities(data, resolution=0.1)
    fix = re.search(r"(np\.where\(data < 0, 0\.5, data / 100\))", str(err.value))
    assert fix is not None
    grid = OccupancyGrid.from_probabilities(eval(fix.group(1)), resolution=0.1)
    np.testing.assert_array_equal(grid.unknown(), data == -1)
    np.testing.assert_array_equal(grid.occupied(), data == 100)
