"""`UpdateResult(status=)` and seeds take 0-d integer arrays, like every integer (review 20)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import box

from navkit.estimation import FusionStatus, UpdateResult
from navkit.sim import Lidar, World

_INT_DTYPES = [np.int8, np.int16, np.int32, np.int64, np.uint8, np.uint16, np.uint32, np.uint64]


@given(st.sampled_from([s for s in FusionStatus if s is not FusionStatus.ACCEPTED]),
       st.sampled_from(_INT_DTYPES))  # fmt: skip
def test_a_0d_integer_status_is_its_code(status: FusionStatus, dtype: type) -> None:
    result = UpdateResult(False, 0.5, np.array([0.1]), status=np.array(int(status), dtype=dtype))
    assert result.status is status


def test_0d_statuses_that_are_not_codes_are_refused_as_before() -> None:
    with pytest.raises(ValueError, match="status must be a FusionStatus code"):
        UpdateResult(False, 0.5, np.array([0.1]), status=np.array(99))
    for refused in (np.array(True), np.array(2.0)):
        with pytest.raises(TypeError, match="status must be a FusionStatus or None"):
            UpdateResult(False, 0.5, np.array([0.1]), status=refused)
    # A masked code: the ValueError FusionStatus gives it, naming status (review 22).
    with pytest.raises(ValueError, match="status has masked entries"):
        UpdateResult(False, 0.5, np.array([0.1]), status=np.ma.array(1, mask=True))


@settings(max_examples=20, deadline=None)
@given(st.integers(0, 2**32 - 1), st.sampled_from([np.int64, np.uint32, np.uint64]))
def test_a_0d_integer_seed_draws_as_its_integer(seed: int, dtype: type) -> None:
    world = World(box(0.0, 0.0, 4.0, 3.0).exterior)
    lidar = Lidar(n_beams=16)  # noisy: the seed decides every range
    drawn = lidar.scan(world, (1.0, 1.0, 0.0), seed=np.array(seed, dtype=dtype))
    twin = lidar.scan(world, (1.0, 1.0, 0.0), seed=seed)
    np.testing.assert_array_equal(drawn.ranges, twin.ranges)
    with pytest.raises(TypeError, match="seed must be a numpy Generator, an int seed or None"):
        lidar.scan(world, (1.0, 1.0, 0.0), seed=np.array(float(seed)))
