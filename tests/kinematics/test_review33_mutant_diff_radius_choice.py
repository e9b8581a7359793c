"""``DiffDrive`` takes one common radius or both individual ones, never a mix (review 33, mutants).

The suite gave ``wheel_radius`` together with both individual radii. The mutant
``and`` for ``or`` in the constructor's test for individual radii passed it:
``wheel_radius`` with only ``left_radius`` (a calibrated left wheel) made a
drive of two equal wheels and dropped ``left_radius`` without a word. Checked:
fails on that mutant of ``_diff.py``, passes on HEAD.
"""

from __future__ import annotations

import pytest

from navkit.kinematics import DiffDrive


@pytest.mark.parametrize("side", ["left_radius", "right_radius"])
def test_a_common_radius_with_one_individual_radius_is_refused(side: str) -> None:
    with pytest.raises(ValueError, match=r"^give either wheel_radius or left_radius/right_radius"):
        DiffDrive(track=0.3, wheel_radius=0.05, **{side: 0.06})
