"""Renamed kinematics keywords: the old names still work for a release, with a warning.

``OmniDrive.saturate(max_speed=)`` is now ``max_wheel_speed=`` (rad/s, the name
``sim.Robot`` uses; ``max_speed`` is a body speed in m/s everywhere else).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from navkit.kinematics import OmniDrive

SPEEDS = [10.0, -20.0, 5.0]


def drive() -> OmniDrive:
    return OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)


def test_saturate_new_name_does_not_warn() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out = drive().saturate(SPEEDS, max_wheel_speed=10.0)
    np.testing.assert_array_equal(out, [5.0, -10.0, 2.5])


def test_saturate_old_name_warns_and_gives_the_same_result() -> None:
    new = drive().saturate(SPEEDS, max_wheel_speed=8.0)
    with pytest.warns(DeprecationWarning, match="max_speed is deprecated.*max_wheel_speed") as rec:
        old = drive().saturate(SPEEDS, max_speed=8.0)
    np.testing.assert_array_equal(old, new)
    assert rec[0].filename == __file__


def test_saturate_both_names_or_neither_is_a_type_error() -> None:
    with pytest.raises(TypeError, match="both max_wheel_speed and its old name max_speed"):
        drive().saturate(SPEEDS, max_wheel_speed=8.0, max_speed=8.0)
    with pytest.raises(TypeError, match="max_wheel_speed"):
        drive().saturate(SPEEDS)


def test_saturate_errors_name_the_new_keyword() -> None:
    with pytest.raises(ValueError, match="max_wheel_speed"):
        drive().saturate(SPEEDS, max_wheel_speed=0.0)
