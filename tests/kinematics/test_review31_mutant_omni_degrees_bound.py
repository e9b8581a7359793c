"""OmniDrive's degrees warning starts beyond one full turn (review 31, mutants).

``OmniDrive`` warns when every wheel angle is a whole number and one lies
beyond 2π (a layout in degrees). The suite's layouts ([30, 150, 270] and the
like) are far beyond, so a bound of 3π passed it: then [0, 2, 7] (7 > 2π)
went without a word. Checked: the first test fails on the mutant ``2 * np.pi``
-> ``3 * np.pi`` of ``_omni.py``, the last on the mutant that dropped
``saturate``'s refusal of a missing limit; all pass on HEAD.
"""

from __future__ import annotations

import math
import warnings

import pytest

from navkit.kinematics import OmniDrive


@pytest.mark.parametrize("angles", [[0.0, 2.0, 7.0], [-7.0, 0.0, 3.0], [1.0, 4.0, 9.0]])
def test_whole_numbers_just_beyond_a_full_turn_warn(angles: list[float]) -> None:
    assert max(abs(a) for a in angles) > 2.0 * math.pi
    with pytest.warns(UserWarning, match=r"wheel_angles .*look like degrees"):
        OmniDrive(angles, wheel_radius=0.05, base_radius=0.2)


@pytest.mark.parametrize("angles", [[0.0, 3.0, 6.0], [-6.0, -2.0, 2.0]])
def test_whole_numbers_within_a_full_turn_do_not_warn(angles: list[float]) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        drive = OmniDrive(angles, wheel_radius=0.05, base_radius=0.2)
    assert drive.n_wheels == 3


def test_saturate_without_a_limit_is_refused_as_python_refuses_a_missing_keyword() -> None:
    # The limit has a default only for the deprecated ``max_speed`` spelling; a call
    # with neither is refused in Python's words for a missing keyword-only argument
    # (a mutant that let it through to the number check said "got NoneType").
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    with pytest.raises(
        TypeError, match=r"^saturate\(\) missing required keyword-only argument: 'max_wheel_speed'$"
    ):
        drive.saturate([1.0, 2.0, 3.0])
