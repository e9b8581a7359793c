"""PlanarFusion with ``history`` interrupted anywhere in the general (validating) path.

Mutation gap (MUTANT6): the general path of the updates (taken with ``history``
for a stamp that is not a Python float, or one equal to the newest kept step's)
without its ``_settle`` under the step's try passed every test: the interrupt
tests drove the fast path only. Interrupted as the step returned, such a filter
kept an overflowed prediction (time 1e300, a NaN covariance), or took the
measurement without keeping it for ``history`` (a late measurement fused next
dropped it).

The oracle is the uninterrupted filter: interrupted at any point CPython
delivers a ``KeyboardInterrupt``, the filter is as before the call or as after
it; then the same later measurements give the same numbers, and a late
measurement is either refused (the history dropped, as documented) or fused
exactly as the uninterrupted filter fuses it.
"""

from __future__ import annotations

import contextlib
import copy
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from interrupt_points import interrupted_at
from navkit.errors import FilterError
from navkit.estimation import FusionStatus, PlanarFusion

_CALLS: dict[str, Callable[[PlanarFusion, Any], Any]] = {
    "update_odometry": lambda f, t: f.update_odometry(
        t, 1.0, 0.1, v_variance=0.01, omega_variance=0.01
    ),
    "update_yaw": lambda f, t: f.update_yaw(t, 0.3, variance=0.01),
    "update_yaw_rate": lambda f, t: f.update_yaw_rate(t, 0.2, variance=0.01),
}


def _fusion_in_motion() -> PlanarFusion:
    fusion = PlanarFusion([0.0, 0.0, 0.0, 1.0, 0.5, 0.0], t0=0.0, history=1.0)
    fusion.update_odometry(0.1, 1.0, 0.1, v_variance=0.01, omega_variance=0.01)
    return fusion


def _estimate(fusion: PlanarFusion) -> tuple[Any, ...]:
    return fusion.t, fusion.x.tobytes(), fusion.P.tobytes()


def _go_on(fusion: PlanarFusion) -> tuple[Any, ...]:
    fusion.update_odometry(0.3, 1.0, 0.1, v_variance=0.01, omega_variance=0.01)
    fusion.update_yaw(0.4, 0.2, variance=0.01)
    return _estimate(fusion)


def _late(fusion: PlanarFusion) -> tuple[Any, ...]:
    """A yaw reading older than the filter time but within ``history``."""
    result = fusion.update_yaw(0.15, 0.05, variance=0.01)
    return FusionStatus(result.status).name, _estimate(fusion)


@pytest.mark.parametrize("method", sorted(_CALLS))
@pytest.mark.parametrize("t", [np.float64(1e300), np.float64(0.2), 0.1, 2])
def test_interrupted_anywhere_the_filter_is_as_before_or_after(method: str, t: Any) -> None:
    call = _CALLS[method]
    before = _fusion_in_motion()
    after = copy.deepcopy(before)
    with contextlib.suppress(FilterError):
        call(after, t)
    wanted = {_estimate(before): before, _estimate(after): after}
    k = 1
    while True:
        fusion = _fusion_in_motion()

        def quiet(fusion: PlanarFusion = fusion) -> None:
            with contextlib.suppress(FilterError):
                call(fusion, t)

        if not interrupted_at(k, quiet):
            break
        state = _estimate(fusion)
        assert state in wanted, f"interrupted at point {k}: t={fusion.t}"
        assert np.isfinite(fusion.P).all()
        model = wanted[state]
        assert _go_on(copy.deepcopy(fusion)) == _go_on(copy.deepcopy(model)), k
        late = _late(copy.deepcopy(fusion))
        if late[0] != "OUT_OF_ORDER":  # refused: the history was dropped
            assert late == _late(copy.deepcopy(model)), k
        k += 1
    assert k > 5  # the points were there to try
