"""The "[x, y] given for a pose" hint is given for two numbers only (review 11).

``as_pose`` added "a Pose2D is [x, y, theta], so give all three" to the error
for any list of length 2: two poses (``[[x, y, θ], [x, y, θ]]``, where one is
wanted) or a ragged pair were told to give three numbers, which would not fix
them.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.geometry import as_pose


@pytest.mark.parametrize(
    "value",
    [
        [[1.0, 2.0, 0.5], [3.0, 4.0, 0.1]],  # two poses as lists
        ([1.0, 2.0], [3.0, 4.0]),  # two points
        [1.0, [2.0, 3.0]],  # ragged
    ],
)
def test_a_pair_of_sequences_gets_no_give_all_three_hint(value: Any) -> None:
    with pytest.raises(ValueError, match="pose") as err:
        as_pose(value)
    assert "give all three" not in str(err.value)


@pytest.mark.parametrize("value", [[1.0, 2.0], (1, 2), np.array([1.0, 2.0])])
def test_two_numbers_still_get_the_hint(value: Any) -> None:
    with pytest.raises(ValueError, match="give all three"):
        as_pose(value)
