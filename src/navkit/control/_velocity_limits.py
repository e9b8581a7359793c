"""Acceleration and deceleration limits on a velocity change."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.products import ordered_dot
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array
from navkit.control._ranges import quantity
from navkit.geometry import Twist2D

__all__ = ["limit_velocity_change"]


def limit_velocity_change(
    previous: ArrayLike,
    desired: ArrayLike,
    *,
    max_accel: float,
    max_decel: float,
    dt: float,
) -> FloatArray:
    """Move a velocity toward ``desired`` within acceleration and deceleration limits.

    The result lies on the segment from ``previous`` to ``desired``, as far along
    it as the limits allow: a change that leaves the speed ``‖v‖`` at most its
    previous value is a deceleration and may be up to ``max_decel·dt`` long; a
    change that raises the speed is an acceleration, at most ``max_accel·dt``.
    Works for any dimension (2-D velocity vectors, or 1-D forward speeds).

    Parameters
    ----------
    previous, desired : array_like, shape (k,)
        Previous and requested velocity (m/s), finite.
    max_accel, max_decel : float
        Limits in m/s², in [1e-6, 1e6].
    dt : float
        Time step in seconds, in [1e-6, 1e6].

    Returns
    -------
    ndarray, shape (k,)
        The limited velocity (a new array; the inputs are not modified).

    Raises
    ------
    TypeError
        Arguments that are not real numbers (complex numbers, strings and
        booleans are refused), naming them; a :class:`~navkit.geometry.Twist2D`,
        whose ``omega`` is no velocity in m/s (the message says what to pass).
    ValueError
        Non-finite velocities, shapes that differ, limits or ``dt`` outside
        their ranges, or velocities so far apart that their difference
        overflows float64.

    Examples
    --------
    >>> limit_velocity_change([0.0, 0.0], [1.0, 0.0], max_accel=0.5, max_decel=2.0,
    ...                       dt=0.1)  # speeding up
    array([0.05, 0.  ])
    >>> limit_velocity_change([1.0, 0.0], [0.0, 0.0], max_accel=0.5, max_decel=2.0,
    ...                       dt=0.1)  # braking
    array([0.8, 0. ])
    """
    for value, name in ((previous, "previous"), (desired, "desired")):
        if isinstance(value, Twist2D):
            # Review 34: one norm over (vx, vy, omega) would add m/s to rad/s.
            raise TypeError(
                f"{name} is a Twist2D, whose (vx, vy, omega) mixes m/s and rad/s: pass its "
                "linear velocity, [twist.vx, twist.vy] ([twist.vx] for a differential "
                "drive), and limit [twist.omega] in a call of its own"
            )
    prev = as_float_array(previous, "previous", ndim=1)
    want = as_float_array(desired, "desired", shape=prev.shape)
    limits = (
        quantity(max_accel, "max_accel", "m/s²"),
        quantity(max_decel, "max_decel", "m/s²"),
        quantity(dt, "dt", "s"),
    )
    # Velocities near the float limit are reported as a ValueError, without a warning.
    with np.errstate(over="ignore", invalid="ignore"):
        return _limit_change(prev, want, *limits)


def _limit_change(
    prev: FloatArray,
    want: FloatArray,
    max_accel: float,
    max_decel: float,
    dt: float,
    names: str = "previous, desired",
) -> FloatArray:
    """:func:`limit_velocity_change` on validated arrays and limits.

    ``names`` names the arguments in the error raised when ``want - prev``
    overflows float64.
    """
    try:
        # No np.errstate here (it would cost the controller's step more than the rest of
        # this function): the norm of a change beyond about 1e154 overflows (the change
        # is then measured scaled) and may warn.
        delta = want - prev
        # Norms and dot products added in order (not np.linalg.norm / np.dot, whose BLAS
        # kernel differs by CPU: review 34): the same limit, bit for bit, everywhere.
        n = math.sqrt(ordered_dot(delta, delta))
        if n < math.inf:
            u = delta / n if n > 0.0 else delta
        else:
            # The squared norm overflowed (|delta| > 1e154), or delta itself did.
            scale = float(np.max(np.abs(delta)))
            if not scale < math.inf:
                raise ValueError(
                    f"{names}: the velocity change overflows float64 (values far too large)"
                )
            # Each component is finite but the length may not be: the direction from the
            # scaled vector, the length possibly inf (only compared with finite steps).
            scaled = delta / scale
            length = math.sqrt(ordered_dot(scaled, scaled))
            u = scaled / length
            n = scale * length
        if n == 0.0:
            same: FloatArray = prev.copy()
            return same
        # Along prev + t·u the speed is below its start value exactly for 0 < t < t_slow.
        t_slow = max(0.0, -2.0 * ordered_dot(prev, u))
        step_a = max_accel * dt
        step_d = max_decel * dt
        if n <= t_slow:
            t = min(n, step_d)
        elif step_a > t_slow:
            t = min(n, step_a)
        else:
            t = min(t_slow, step_d)
        out: FloatArray = prev + t * u
        return out
    except FloatingPointError:
        # Only under a caller's np.seterr(...="raise"): a norm whose squares underflow
        # (a change of 1e-200 m/s). The work is pure, so it is done again for NumPy's
        # default answer (nothing here divides by zero: no error is hidden). A try
        # costs the controller's step nothing, an np.errstate per call a microsecond.
        with np.errstate(all="ignore"):
            return _limit_change(prev, want, max_accel, max_decel, dt, names)
