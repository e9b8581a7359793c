"""An old PlanarFusion state, gated and without a clock, loads as built today (review 52, MUTANT32).

FOUND4 migrates a ``PlanarFusion`` pickled before it reduced itself: its
estimate, process noise, gates and time go into a filter as the constructor
builds one. The old pickles of its tests have no gating and a running clock:
mutants dropping the gates (every gate infinite) or reading a clock of NaN
as a time passed them. Here the old state of its 0123de4 pickle is given a
gate probability and no clock (``None`` as then, and NaN).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from test_review52_found_old_pickles import FUSION, _load

from navkit.estimation import PlanarFusion


def _old_state(commit: str) -> Any:
    """The state an old pickle hands to ``__setstate__``, captured as it loads."""
    captured: list[Any] = []
    restore = PlanarFusion.__setstate__
    try:
        PlanarFusion.__setstate__ = lambda self, state: captured.append(state)  # type: ignore[method-assign]
        _load(FUSION[commit], compressed=True)
    finally:
        PlanarFusion.__setstate__ = restore  # type: ignore[method-assign]
    (state,) = captured
    return state


@pytest.mark.parametrize("clock", [None, math.nan])
def test_an_old_gated_filter_without_a_clock_fuses_as_one_built_today(clock: float | None) -> None:
    commit = next(c for c in sorted(FUSION) if "_t" in _old_state(c)[1])
    instance, slots = _old_state(commit)
    fresh = PlanarFusion(
        np.array(slots["_x"], dtype=np.float64).reshape(6),
        slots["_p"],
        process_noise=slots["_q"],
        gate_probability=0.99,
    )
    old_slots = dict(slots, _t=clock, _gates=fresh._gates.copy())
    old = PlanarFusion.__new__(PlanarFusion)
    old.__setstate__((instance, old_slots))
    assert old.t is None and fresh.t is None
    # An outlier the 0.99 gate refuses, then readings it takes: the same estimate.
    for filt in (old, fresh):
        filt.update_yaw(0.2, 3.0, variance=1e-4)
        filt.update_yaw(0.3, 0.01, variance=1e-3)
        filt.update_odometry(0.4, 0.4, 0.05, v_variance=0.01, omega_variance=0.01)
    assert old.t == fresh.t == 0.4
    np.testing.assert_array_equal(old.x, fresh.x)
    np.testing.assert_array_equal(old.P, fresh.P)
    # The gate matters here: without it the outlier moves the estimate.
    ungated = PlanarFusion(
        np.array(slots["_x"], dtype=np.float64).reshape(6), slots["_p"], process_noise=slots["_q"]
    )
    ungated.update_yaw(0.2, 3.0, variance=1e-4)
    ungated.update_yaw(0.3, 0.01, variance=1e-3)
    ungated.update_odometry(0.4, 0.4, 0.05, v_variance=0.01, omega_variance=0.01)
    assert not np.array_equal(ungated.x, fresh.x)
