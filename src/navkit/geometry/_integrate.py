"""Exact integration of constant body twists on SE(2)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.validation import as_float_array, finite_float
from navkit.geometry._kernels import integrate_kernel, rollout_kernel
from navkit.geometry._pose import Pose2D, Twist2D

__all__ = ["integrate", "rollout"]


def integrate(pose: Pose2D, twist: Twist2D, dt: float) -> Pose2D:
    """Move ``pose`` by the body twist ``twist`` held constant for ``dt`` seconds.

    Uses the exact SE(2) exponential: a straight line when ``omega == 0`` and a
    circular arc otherwise, evaluated with a ``sinc`` formulation that stays
    accurate as ``omega -> 0`` (no switch-over discontinuity).

    Parameters
    ----------
    pose : Pose2D
        Start pose in the world frame.
    twist : Twist2D
        Body-frame velocity (m/s, m/s, rad/s).
    dt : float
        Duration in seconds, >= 0.

    Returns
    -------
    Pose2D
        The pose after ``dt``.

    Examples
    --------
    >>> import math
    >>> p = integrate(Pose2D(0.0, 0.0, 0.0), Twist2D(1.0, 0.0, math.pi), 1.0)
    >>> round(p.x, 12), round(p.y, 12), round(p.theta, 12)
    (0.0, 0.636619772368, 3.14159265359)
    """
    if not isinstance(pose, Pose2D):
        raise TypeError(f"pose must be a Pose2D, got {type(pose).__name__}")
    if not isinstance(twist, Twist2D):
        raise TypeError(f"twist must be a Twist2D, got {type(twist).__name__}")
    step = finite_float(dt, "dt")
    if step < 0.0:
        raise ValueError(f"dt must be >= 0, got {step}")
    x, y, th = integrate_kernel(pose.x, pose.y, pose.theta, twist.vx, twist.vy, twist.omega, step)
    return Pose2D(x, y, th)


def rollout(pose: Pose2D, twists: ArrayLike, dt: ArrayLike) -> NDArray[np.float64]:
    """Integrate a sequence of body twists, each held for its time step.

    Parameters
    ----------
    pose : Pose2D
        Start pose.
    twists : array_like, shape (N, 3)
        Rows ``[vx, vy, omega]`` in the body frame (m/s, m/s, rad/s).
    dt : float or array_like, shape (N,)
        Time step(s) in seconds, >= 0.

    Returns
    -------
    ndarray, shape (N + 1, 3)
        Poses ``[x, y, theta]``; row 0 is ``pose``, row i the pose after twist i-1.
        Identical to repeated :func:`integrate` calls.

    Examples
    --------
    >>> traj = rollout(Pose2D(0.0, 0.0), [[1.0, 0.0, 0.0]] * 3, 0.5)
    >>> traj[:, 0]
    array([0. , 0.5, 1. , 1.5])
    """
    if not isinstance(pose, Pose2D):
        raise TypeError(f"pose must be a Pose2D, got {type(pose).__name__}")
    tw = as_float_array(twists, "twists", shape=(None, 3))
    n = tw.shape[0]
    steps = as_float_array(dt, "dt")
    if steps.ndim == 0:
        steps = np.full(n, float(steps))
    elif steps.shape != (n,):
        raise ValueError(f"dt must be a scalar or have shape ({n},), got {steps.shape}")
    if np.any(steps < 0.0):
        raise ValueError("dt must be >= 0")
    out = np.empty((n + 1, 3), dtype=np.float64)
    rollout_kernel(
        pose.x, pose.y, pose.theta, np.ascontiguousarray(tw), np.ascontiguousarray(steps), out
    )
    return out
