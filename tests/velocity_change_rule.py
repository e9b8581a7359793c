"""The rule that limits a velocity change, checked on consecutive commands.

Shared by the tests of ``limit_velocity_change`` and of the controllers that
apply it (``tests/control``), with the rate and period strategies they draw.
"""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

rate = st.floats(0.1, 5.0)
period = st.floats(0.005, 0.5)
TOL = 1e-9


def check_change(prev: np.ndarray, new: np.ndarray, accel: float, decel: float, dt: float) -> None:
    """The rule: a change that raises the speed is limited by accel, any other by decel.

    A speed unchanged to within rounding may be classed either way.
    """
    step = float(np.linalg.norm(new - prev))
    gain = float(np.linalg.norm(new) - np.linalg.norm(prev))
    if abs(gain) <= TOL:
        limit = max(accel, decel) * dt
    elif gain > 0.0:
        limit = accel * dt
    else:
        limit = decel * dt
    assert step <= limit * (1 + 1e-9) + TOL, (prev, new, step, limit)
