"""Masked tick readings and memoryview noise tables (review 11).

``EncoderReading`` read a masked ``ticks`` array as its data: a reading masked
as "no value" (a dropped CAN frame) became the counter value underneath.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.sim import EncoderReading, RangeNoise


def test_masked_ticks_are_refused() -> None:
    ticks = np.ma.array([10, 12], mask=[True, False])
    with pytest.raises(ValueError, match=r"^ticks has masked entries"):
        EncoderReading(0.02, ticks)


def test_masked_ticks_without_masked_entries_are_their_data() -> None:
    reading = EncoderReading(0.02, np.ma.array([10, 12]))
    assert reading.ticks.tolist() == [10, 12]
    assert type(reading.ticks) is np.ndarray


def test_range_noise_limits_as_a_two_d_memoryview_are_a_type_error() -> None:
    # Python cannot iterate a 2-D memoryview (NotImplementedError): read as its array.
    with pytest.raises(TypeError, match=r"^limits\[0\] must be a real number"):
        RangeNoise(limits=np.zeros((2, 1)).data)  # type: ignore[arg-type]


def test_range_noise_limits_as_a_one_d_memoryview_are_its_values() -> None:
    view = np.array([3.0, np.inf]).data
    assert RangeNoise(limits=view).limits == RangeNoise(limits=(3.0, np.inf)).limits  # type: ignore[arg-type]
