"""DiffDrive.odometry_step_batch without its full-size temporaries, the same bits (review 28).

The result and up to five arrays of a row's size at once (two of them the
constant ``vy`` 0 and ``dt`` 1 of the general SE(2) exponential) peaked at 2.3
times the result; now 1.7 ("arc", "first_order") and 2.0 ("midpoint").
"""

from __future__ import annotations

import numpy as np
import pytest

from memory_peak import peak_bytes
from navkit._shared.se2 import exp_body
from navkit.geometry import wrap_angle
from navkit.kinematics import DiffDrive

N = 200_000
METHODS = ("arc", "midpoint", "first_order")


def _distances(n: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(28)
    dl = rng.normal(0.0, 0.05, n)
    dr = rng.normal(0.0, 0.05, n)
    dl[::7] = dr[::7]  # straight ahead
    dl[::11] = -dr[::11]  # on the spot
    dl[::13], dr[::13] = 0.0, -0.0
    dl[::17] *= 1e6  # turns of many laps, wrapped
    return dl, dr


@pytest.mark.parametrize(
    ("method", "bound"), [("arc", 1.9), ("midpoint", 2.2), ("first_order", 1.9)]
)
def test_odometry_step_batch_peaks_under_twice_its_result(method: str, bound: float) -> None:
    drive = DiffDrive(track=0.5, wheel_radius=0.1)
    dl, dr = _distances(N)
    peak, out = peak_bytes(lambda: drive.odometry_step_batch(dl, dr, method=method))  # type: ignore[arg-type]
    assert peak < bound * out.nbytes, f"{method}: peak {peak / out.nbytes:.2f} times the result"


@pytest.mark.parametrize("radii", [(0.1, 0.1), (0.1, 0.1001), (0.05, 0.2)])
def test_the_rows_are_those_of_the_plain_vectorised_formulas_bit_for_bit(
    radii: tuple[float, float],
) -> None:
    drive = DiffDrive(track=0.3, left_radius=radii[0], right_radius=radii[1])
    dl, dr = _distances(5_000)
    before = (dl.copy(), dr.copy())
    dc = 0.5 * dr + 0.5 * dl
    dth = (dr - dl) / drive.track
    # The general SE(2) exponential, one row at a time (vy 0, dt 1).
    arc = np.array([exp_body(float(c), 0.0, float(t), 1.0) for c, t in zip(dc, dth, strict=True)])
    expected = {
        "arc": arc[:, :2],
        "midpoint": np.column_stack((dc * np.cos(0.5 * dth), dc * np.sin(0.5 * dth))),
        "first_order": np.column_stack((dc, np.zeros_like(dc))),
    }
    for method in METHODS:
        steps = drive.odometry_step_batch(dl, dr, method=method)  # type: ignore[arg-type]
        assert steps.flags.c_contiguous
        # tobytes: the signs of zeros too.
        assert steps[:, :2].tobytes() == np.ascontiguousarray(expected[method]).tobytes()
        assert steps[:, 2].tobytes() == wrap_angle(dth).tobytes()
    np.testing.assert_array_equal(dl, before[0])  # inputs untouched
    np.testing.assert_array_equal(dr, before[1])
