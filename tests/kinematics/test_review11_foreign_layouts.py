"""Results do not depend on the memory layout of the input (review 11).

``OmniDrive.forward`` multiplies by the forward matrix with NumPy's ``@``: a
reversed or broadcast (zero-stride) view of the wheel speeds took NumPy's own
summation loop instead of BLAS's, so the twist differed in the last bits from
the one for the same values in a plain array.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.kinematics import OmniDrive

DRIVE = OmniDrive([0.5, 2.6, 4.7], wheel_radius=0.05, base_radius=0.2)
SPEED = st.floats(-100.0, 100.0, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(st.lists(SPEED, min_size=3, max_size=3))
def test_forward_of_a_reversed_view_equals_forward_of_the_array(speeds: list[float]) -> None:
    plain = np.array(speeds)
    reversed_view = plain[::-1].copy()[::-1]
    assert reversed_view.strides[0] < 0
    assert DRIVE.forward(reversed_view) == DRIVE.forward(plain)


@settings(max_examples=60, deadline=None)
@given(SPEED)
def test_forward_of_a_broadcast_view_equals_forward_of_the_array(speed: float) -> None:
    view = np.broadcast_to(np.array([speed]), (3,))
    assert DRIVE.forward(view) == DRIVE.forward(np.full(3, speed))


def test_forward_of_a_big_endian_array_equals_forward_of_the_array() -> None:
    speeds = np.array([3.0, -2.0, 1.0])
    assert DRIVE.forward(speeds.astype(">f8")) == DRIVE.forward(speeds)
