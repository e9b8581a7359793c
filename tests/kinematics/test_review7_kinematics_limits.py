"""Documented parameter ranges of navkit.kinematics: accepted at each limit, refused just past it.

The refusal printed the value with ``:g``, which rounds it back onto the limit
("track must be in [1e-06, 1e+06] m, got 1e+06" for 1e6 plus one ulp); the
message now shows the value given.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import pytest

from navkit.kinematics import DiffDrive, OmniDrive, ticks_to_distance

_MAKERS: dict[str, Callable[[float], Any]] = {
    "track": lambda v: DiffDrive(track=v, wheel_radius=0.1),
    "wheel_radius": lambda v: DiffDrive(track=0.3, wheel_radius=v),
    "left_radius": lambda v: DiffDrive(track=0.3, left_radius=v, right_radius=0.1),
    "right_radius": lambda v: DiffDrive(track=0.3, left_radius=0.1, right_radius=v),
    "base_radius": lambda v: OmniDrive.three_wheel(wheel_radius=0.1, base_radius=v),
    "ticks_per_rev": lambda v: ticks_to_distance(1.0, ticks_per_rev=v, wheel_radius=0.1),
}
_OMNI_WHEEL = lambda v: OmniDrive.three_wheel(wheel_radius=v, base_radius=0.1)  # noqa: E731
_TICKS_WHEEL = lambda v: ticks_to_distance(1.0, ticks_per_rev=100.0, wheel_radius=v)  # noqa: E731
_CASES = [*_MAKERS.items(), ("wheel_radius", _OMNI_WHEEL), ("wheel_radius", _TICKS_WHEEL)]


@pytest.mark.parametrize(("name", "make"), _CASES)
def test_limits_are_inclusive_and_the_refusal_shows_the_value(
    name: str, make: Callable[[float], Any]
) -> None:
    low, high = (1.0, 1e12) if name == "ticks_per_rev" else (1e-6, 1e6)
    make(low)
    make(high)
    for outside in (math.nextafter(low, 0.0), math.nextafter(high, math.inf)):
        with pytest.raises(ValueError, match=rf"^{name} must be in \[") as info:
            make(outside)
        assert str(info.value).endswith(f"got {outside!r}")
