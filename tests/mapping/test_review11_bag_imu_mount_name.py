"""BagImu.to_base's errors name the keyword the caller wrote, as imu_to_base's do.

``to_base(mounting=bad)`` (the deprecated name) raised ``mount must ...``:
the caller wrote no ``mount``. ``imu_to_base(mounting=bad)`` names
``mounting``, and so does every other renamed option.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
import pytest

from navkit.geometry import imu_to_base, rpy_to_quaternion
from navkit.mapping.io import BagImu


def _imu() -> BagImu:
    return BagImu(
        "/imu", "imu_link", [0.0, 0.1], [0.0, 0.1],
        [[0.0, 0.0, 0.0, 1.0]] * 2, [[0.0, 0.0, 0.2]] * 2, [[0.0, 1.0, 9.8]] * 2,
        *[np.stack([np.eye(3)] * 2)] * 3,
    )  # fmt: skip


@pytest.mark.parametrize(
    ("bad", "error", "message"),
    [
        ([0.0, 0.0, 0.0, 0.0], ValueError, "non-zero quaternion"),
        ([0.0, 0.0, 1.0], ValueError, "length 4"),
        ([0.0, 0.0, np.nan, 1.0], ValueError, "finite"),
        (["a", "b", "c", "d"], TypeError, ""),
    ],
)
@pytest.mark.parametrize("name", ["mount", "mounting"])
def test_errors_name_the_keyword_written(
    name: str, bad: Any, error: type[Exception], message: str
) -> None:
    kwargs: dict[str, Any] = {name: bad}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        with pytest.raises(error) as raised:
            _imu().to_base(**kwargs)
        with pytest.raises(error) as reference:
            imu_to_base([0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], **kwargs)
    assert str(raised.value).startswith(f"{name} ")
    assert message in str(raised.value)
    assert str(raised.value) == str(reference.value)


def test_the_old_name_still_gives_the_same_readings_with_one_warning() -> None:
    imu, mount = _imu(), rpy_to_quaternion(0.1, -0.2, 0.3)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        old = imu.to_base(mounting=mount)
    assert [w.category for w in caught] == [DeprecationWarning]
    assert caught[0].filename == __file__
    new = imu.to_base(mount)
    for field in ("orientations", "angular_velocities", "linear_accelerations",
                  "orientation_covariances", "angular_velocity_covariances",
                  "linear_acceleration_covariances"):  # fmt: skip
        assert np.array_equal(getattr(old, field), getattr(new, field)), field
