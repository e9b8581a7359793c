"""A scalar where an IMU vector is wanted is a ValueError naming the argument.

Review 40 (mutation testing, MUTANT11). ``_vectors``'s ``v.ndim == 0`` check read as
``v.ndim == -1`` passed every geometry test: a scalar angular velocity or
acceleration then reached ``v.shape[-1]`` and ``imu_to_base`` and ``ImuInBase``
raised ``IndexError: tuple index out of range`` instead of the documented
``ValueError`` naming the argument and its shape.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.geometry import ImuInBase, imu_to_base

Q = [0.0, 0.0, 0.0, 1.0]
W = [0.0, 0.0, 0.1]
A = [0.0, 0.0, 9.8]
_CALLS: list[tuple[Callable[[Any, Any], object], str]] = [
    (lambda w, a: imu_to_base(Q, w, a, mount=Q), "imu_to_base"),
    (lambda w, a: ImuInBase(Q, w, a), "ImuInBase"),
]


@pytest.mark.parametrize(("call", "label"), _CALLS)
@pytest.mark.parametrize("scalar", [1.0, np.float64(9.8), np.array(0.5), 3])
def test_a_scalar_vector_is_refused_naming_it(
    call: Callable[[Any, Any], object], label: str, scalar: Any
) -> None:
    with pytest.raises(ValueError, match=r"angular_velocities must have shape \(\.\.\., 3\)"):
        call(scalar, A)
    with pytest.raises(ValueError, match=r"linear_accelerations must have shape \(\.\.\., 3\)"):
        call(W, scalar)
    # The vectors themselves are accepted (the call is otherwise valid).
    call(W, A)
