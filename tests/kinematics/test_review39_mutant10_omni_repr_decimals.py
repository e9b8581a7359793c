"""OmniDrive's repr spells angles in degrees of at most 6 decimals, else in radians.

Review 39 (mutation testing, MUTANT10): ``_degrees_text`` trying 7 decimals
(``range(8)``) passed every test; the docstring promises at most 6. Oracle: the
float the degrees text reads back to (``np.radians``), and ``eval`` of the repr.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.kinematics import OmniDrive

radians = np.radians  # the name the repr uses


@pytest.mark.parametrize(
    ("degrees", "spelled"),
    [
        ([12.345678, 150.0, 270.0], "radians([12.345678, 150, 270])"),  # 6 decimals
        ([12.3456789, 150.0, 270.0], None),  # 7 decimals: radians
        ([-0.0000001, 90.0, 200.0], None),
    ],
)
def test_degrees_need_at_most_six_decimals(degrees: list[float], spelled: str | None) -> None:
    angles = np.radians(degrees)
    drive = OmniDrive(angles, wheel_radius=0.05, base_radius=0.2)
    text = repr(drive)
    if spelled is not None:
        assert f"wheel_angles={spelled}," in text
    else:
        assert "radians(" not in text
        assert f"wheel_angles={[float(a) for a in angles]!r}," in text
    back = eval(text)
    np.testing.assert_array_equal(back.wheel_angles, drive.wheel_angles)
