"""An empty measurement is refused, naming ``z``, the filter unchanged (review 26, coverage).

The branch refusing ``z`` of no components was never run by the default suite.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter


@pytest.mark.parametrize("z", [[], np.zeros(0), ()], ids=["list", "array", "tuple"])
def test_an_empty_measurement_is_refused_naming_z(z: object) -> None:
    ekf = ExtendedKalmanFilter([0.0, 1.0], np.diag([1.0, 2.0]))
    ekf.update([0.5], lambda x: x[:1], np.array([[1.0, 0.0]]), [[1.0]])  # a buffer exists
    before = (ekf.x.tobytes(), ekf.P.tobytes())
    with pytest.raises(ValueError, match="z must have at least one component"):
        ekf.update(z, lambda x: x[:0], np.zeros((0, 2)), np.zeros((0, 0)))
    assert (ekf.x.tobytes(), ekf.P.tobytes()) == before
    # The filter goes on as before the refused call.
    assert ekf.update([0.5], lambda x: x[:1], np.array([[1.0, 0.0]]), [[1.0]]).accepted
