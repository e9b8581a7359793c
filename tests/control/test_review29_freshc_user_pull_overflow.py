"""A user's pull whose finite components overflow its length (review 29, FRESHC).

``PotentialFieldController`` measures the attraction with ``np.hypot`` to clip it
to ``max_speed``. A user field (navkit's own stay below 1e22) may return finite
components whose length is beyond float64, e.g. ``(1.5e308, 1.5e308)``: NumPy
warned "overflow encountered in hypot" (a ``RuntimeWarning`` escaping
``step`` under ``-W error``) and the length came out ``inf``, so the clip
scaled the pull to zero: the robot stood still instead of heading along it at
``max_speed``. It now heads along the pull at ``max_speed``, with no warning.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pytest
from numpy.typing import NDArray

from navkit.control import PotentialFieldController
from navkit.planning import AttractiveField

F64 = NDArray[np.float64]


@dataclass(frozen=True, slots=True, eq=False, repr=False)
class Steady(AttractiveField):
    """A pull of fixed components wherever the goal is (the pose ignored)."""

    fx: float = 1.5e308
    fy: float = 1.5e308

    def _potential(self, pts: F64) -> F64:
        return np.zeros(pts.shape[0])

    def _force(self, pts: F64) -> F64:
        return np.tile([self.fx, self.fy], (pts.shape[0], 1))


@pytest.mark.parametrize(("fx", "fy"), [(1.5e308, 1.5e308), (1.5e308, -1.2e308), (-1.7e308, 1e308)])
@pytest.mark.parametrize("max_speed", [0.5, 3.0])
def test_an_overflowing_pull_heads_along_it_at_max_speed(
    fx: float, fy: float, max_speed: float
) -> None:
    assert not math.hypot(fx, fy) < math.inf  # its length is beyond float64
    ctl = PotentialFieldController(Steady((0.0, 0.0), fx=fx, fy=fy), max_speed=max_speed)
    # Before: [0, 0] and a RuntimeWarning (an error under filterwarnings = error).
    want = ctl.desired_velocity((0.0, 0.0, 0.0), (1.0, 1.0))
    unit = np.array([fx, fy]) / 1e308
    unit /= np.hypot(unit[0], unit[1])
    np.testing.assert_allclose(want, max_speed * unit, rtol=1e-12, atol=0)


def test_a_step_under_an_overflowing_pull_accelerates_along_it() -> None:
    ctl = PotentialFieldController(Steady((0.0, 0.0)), max_speed=0.5, max_accel=1.0)
    cmd = ctl.step((0.0, 0.0, 0.0), (1.0, 1.0, 0.0), 0.1)
    # max_accel × dt = 0.1 m/s along the pull's direction (45°).
    assert cmd.vx == pytest.approx(0.1 / math.sqrt(2.0), rel=1e-12)
    assert cmd.vy == pytest.approx(0.1 / math.sqrt(2.0), rel=1e-12)
