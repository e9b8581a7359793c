"""Past the exact NIS's cap the gate decides on a midpoint within the bounds (review 44, EKFCHECK).

``_gate_past_the_cap`` gated on ``0.5 * low + 0.5 * high``: with subnormal bounds
each half rounds to even, (3, 3) times 2⁻¹⁰⁷⁴ gave 4 and (5, 5) gave 4, so a NIS at
most the gate was gated and one above it passed. Now the midpoint is rounded into
the bounds (``_midpoint``).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import example, given
from hypothesis import strategies as st

import navkit.estimation._ekf_kernels as kernels

_TINY = math.ulp(0.0)


@given(
    low=st.floats(0.0, 1e308),
    high=st.floats(0.0, 1e308),
)
@example(low=3 * _TINY, high=3 * _TINY)  # 4 before
@example(low=5 * _TINY, high=5 * _TINY)  # 4 before
@example(low=_TINY, high=_TINY)  # 0 before
def test_the_midpoint_lies_within_the_bounds(low: float, high: float) -> None:
    low, high = min(low, high), max(low, high)
    middle = kernels._midpoint(low, high)
    assert low <= middle <= high
    # Within half an ulp (or the least subnormal) of the exact midpoint.
    assert abs(middle - (low / 2 + high / 2)) <= max(math.ulp(high), _TINY)


@pytest.mark.parametrize(
    ("bounds", "gate", "status"),
    [
        ((3 * _TINY, 3 * _TINY), 3 * _TINY, kernels.OK),  # GATED before
        ((5 * _TINY, 5 * _TINY), 4 * _TINY, kernels.GATED),  # OK before
    ],
)
def test_the_gate_decides_on_a_nis_within_the_bounds(
    bounds: tuple[float, float], gate: float, status: int
) -> None:
    p, h, r, y = np.eye(2), np.eye(2), np.eye(2), np.ones(2)
    rbuf = kernels.new_rbuf(2, 2)
    kernels.set_gate(rbuf, gate)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(kernels, "_exact_nis_work", lambda *_: math.inf)
        patch.setattr(kernels, "_nis_interval", lambda *_: bounds)
        assert kernels._gate_past_the_cap(p, h, r, y, rbuf, refuse=True) == status
    assert bounds[0] <= kernels.rbuf_nis(rbuf) <= bounds[1]
