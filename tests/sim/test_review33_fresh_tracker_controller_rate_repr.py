"""Review 33 (FRESH): ``TrackerController``'s repr gives back its control period.

Review 32 printed the rate back from the period rounded to 15 digits, so that
``1 / (1 / rate)`` printed as the rate given; but a rate of 16 or 17
significant digits lost its last ones: ``control_rate=1/3`` printed
``0.333333333333333``, a controller of period 3.000000000000003 s instead of 3 s.
The repr now prints the shortest rate of the same period. Checked: against
``_adapters.py`` of HEAD the 1/3, 2/3, 1/7 and π cases fail.
"""

from __future__ import annotations

import math

import pytest

from navkit.control import FollowTheCarrot
from navkit.sim import TrackerController


def _printed_rate(controller: TrackerController[FollowTheCarrot]) -> float:
    text = repr(controller)
    return float(text.split("control_rate=")[1].split(",")[0])


@pytest.mark.parametrize("rate", [1 / 3, 2 / 3, 1 / 7, 20.0, 13.7, 0.1, 1e-6, 123456.789, math.pi])
def test_the_printed_rate_has_the_controllers_period(rate: float) -> None:
    controller = TrackerController(FollowTheCarrot(), control_rate=rate)
    printed = _printed_rate(controller)
    twin = TrackerController(FollowTheCarrot(), control_rate=printed)
    assert 1.0 / printed == 1.0 / rate  # the same period, bit for bit
    assert repr(twin) == repr(controller)


@pytest.mark.parametrize("rate", [20.0, 3.0, 13.7, 0.1, 50.0, 1 / 3])
def test_a_rate_is_printed_as_given(rate: float) -> None:
    assert f"control_rate={rate!r}," in repr(
        TrackerController(FollowTheCarrot(), control_rate=rate)
    )
