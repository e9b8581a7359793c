"""OmniDrive refuses a layout just beyond its documented condition bound (review 33, mutants).

``OmniDrive`` refuses wheel angles whose layout matrix (rows ``[-sin θi, cos θi,
1]``) has a condition number above 1e10. The suite's singular layouts are far
beyond (parallel wheels: infinite), so a bound of 2e10 passed it: then a layout
with condition number 1.3e10 gave a drive. Oracle: the condition number as the
ratio of extreme singular values from mpmath at 50 digits. Checked: the first
test fails on the mutant ``_MAX_CONDITION = 2e10`` of ``_omni.py``, both pass on
HEAD.
"""

from __future__ import annotations

import mpmath
import pytest

from navkit.kinematics import OmniDrive


def _condition(angles: list[float]) -> float:
    with mpmath.workdps(50):
        rows = [[-mpmath.sin(a), mpmath.cos(a), 1] for a in map(mpmath.mpf, angles)]
        singular = mpmath.svd_r(mpmath.matrix(rows), compute_uv=False)
        return float(max(singular) / min(singular))


# Two wheels 4e-10 rad apart (almost parallel) and a third at a right angle.
_JUST_BEYOND = [0.0, 4e-10, 1.5707963267948966]
# The same, 6e-10 rad apart.
_JUST_WITHIN = [0.0, 6e-10, 1.5707963267948966]


def test_a_layout_just_beyond_the_bound_is_refused() -> None:
    assert 1.2e10 < _condition(_JUST_BEYOND) < 1.5e10
    with pytest.raises(ValueError, match=r"^wheel_angles give a singular layout"):
        OmniDrive(_JUST_BEYOND, wheel_radius=0.05, base_radius=0.2)


def test_a_layout_just_within_the_bound_is_a_drive() -> None:
    assert 0.8e10 < _condition(_JUST_WITHIN) < 0.95e10
    drive = OmniDrive(_JUST_WITHIN, wheel_radius=0.05, base_radius=0.2)
    assert drive.n_wheels == 3
