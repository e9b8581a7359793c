"""Differential-drive kinematics, with unequal wheel radii."""

from __future__ import annotations

from typing import Literal, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.se2 import exp_body, exp_body_array
from navkit._shared.validation import as_float_array, finite_float, positive_float
from navkit.geometry import Twist2D

__all__ = ["DiffDrive", "OdometryMethod"]

OdometryMethod = Literal["arc", "midpoint", "first_order"]
_METHODS = ("arc", "midpoint", "first_order")


class DiffDrive:
    r"""Kinematics of a two-wheeled differential drive.

    With wheel angular speeds :math:`\omega_l, \omega_r` (rad/s), wheel radii
    :math:`R_l, R_r` and track width :math:`D` (distance between the wheel contact
    points):

    .. math::  v = \frac{\omega_r R_r + \omega_l R_l}{2}, \qquad
               \omega = \frac{\omega_r R_r - \omega_l R_l}{D}

    and inversely :math:`\omega_r = (v + \omega D/2)/R_r`,
    :math:`\omega_l = (v - \omega D/2)/R_l`.

    Parameters
    ----------
    track : float
        Distance between the two wheels' contact points, m, > 0.
    wheel_radius : float, optional
        Common wheel radius, m. Give either this or both ``left_radius`` and
        ``right_radius`` (unequal wheels, e.g. from calibration).
    left_radius, right_radius : float, optional
        Individual wheel radii, m, > 0.

    Examples
    --------
    >>> drive = DiffDrive(track=0.3, wheel_radius=0.05)
    >>> drive.forward(omega_left=10.0, omega_right=12.0)
    Twist2D(vx=0.55, vy=0.0, omega=0.333...)
    >>> drive.inverse(Twist2D(0.55, 0.0, 1.0 / 3.0))
    (10.0..., 12.0...)
    """

    __slots__ = ("_left", "_right", "_track")

    def __init__(
        self,
        track: float,
        wheel_radius: float | None = None,
        *,
        left_radius: float | None = None,
        right_radius: float | None = None,
    ) -> None:
        self._track = positive_float(track, "track")
        if wheel_radius is not None:
            if left_radius is not None or right_radius is not None:
                raise ValueError("give either wheel_radius or left_radius/right_radius, not both")
            self._left = self._right = positive_float(wheel_radius, "wheel_radius")
        else:
            if left_radius is None or right_radius is None:
                raise ValueError("give wheel_radius, or both left_radius and right_radius")
            self._left = positive_float(left_radius, "left_radius")
            self._right = positive_float(right_radius, "right_radius")

    @property
    def track(self) -> float:
        """Track width D, m."""
        return self._track

    @property
    def left_radius(self) -> float:
        """Left wheel radius, m."""
        return self._left

    @property
    def right_radius(self) -> float:
        """Right wheel radius, m."""
        return self._right

    def forward(self, omega_left: float, omega_right: float) -> Twist2D:
        """Body twist (vx, 0, omega) from wheel angular speeds in rad/s."""
        wl = finite_float(omega_left, "omega_left") * self._left
        wr = finite_float(omega_right, "omega_right") * self._right
        return Twist2D(0.5 * (wr + wl), 0.0, (wr - wl) / self._track)

    def inverse(self, twist: Twist2D, *, ignore_lateral: bool = False) -> tuple[float, float]:
        """Wheel angular speeds ``(omega_left, omega_right)``, rad/s, for ``twist``.

        Raises
        ------
        ValueError
            If ``twist.vy != 0`` (a differential drive cannot move sideways) unless
            ``ignore_lateral`` is true, in which case ``vy`` is dropped.
        """
        if not isinstance(twist, Twist2D):
            raise TypeError(f"twist must be a Twist2D, got {type(twist).__name__}")
        if twist.vy != 0.0 and not ignore_lateral:
            raise ValueError(
                f"twist has lateral velocity vy={twist.vy}, which a differential drive cannot "
                "follow; pass ignore_lateral=True to drop it"
            )
        half = 0.5 * twist.omega * self._track
        return (twist.vx - half) / self._left, (twist.vx + half) / self._right

    def forward_batch(self, omega_left: ArrayLike, omega_right: ArrayLike) -> NDArray[np.float64]:
        """Body twists (T, 3) ``[vx, 0, omega]`` from wheel speed arrays (T,), rad/s."""
        wl = as_float_array(omega_left, "omega_left", ndim=1) * self._left
        wr = as_float_array(omega_right, "omega_right", shape=(wl.shape[0],)) * self._right
        return np.column_stack((0.5 * (wr + wl), np.zeros_like(wl), (wr - wl) / self._track))

    def inverse_batch(
        self, twists: ArrayLike, *, ignore_lateral: bool = False
    ) -> NDArray[np.float64]:
        """Wheel speeds (T, 2) ``[omega_left, omega_right]``, rad/s, for twists (T, 3)."""
        tw = as_float_array(twists, "twists", shape=(None, 3))
        if not ignore_lateral and np.any(tw[:, 1] != 0.0):
            raise ValueError(
                "twists have non-zero lateral velocity vy, which a differential drive cannot "
                "follow; pass ignore_lateral=True to drop it"
            )
        half = 0.5 * tw[:, 2] * self._track
        return np.column_stack(((tw[:, 0] - half) / self._left, (tw[:, 0] + half) / self._right))

    @overload
    def odometry_step(
        self, d_left: float, d_right: float, method: OdometryMethod = ...
    ) -> tuple[float, float, float]: ...
    @overload
    def odometry_step(
        self, d_left: ArrayLike, d_right: ArrayLike, method: OdometryMethod = ...
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]: ...

    def odometry_step(
        self, d_left: ArrayLike, d_right: ArrayLike, method: OdometryMethod = "arc"
    ) -> (
        tuple[float, float, float]
        | tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]
    ):
        r"""Robot-frame motion from the distances rolled by each wheel.

        With :math:`d_c = (d_r + d_l)/2` and :math:`\Delta\theta = (d_r - d_l)/D`:

        ``"arc"`` (default, exact for constant wheel speeds over the step)
            The wheels roll on concentric circles:
            :math:`dx = d_c \sin\Delta\theta/\Delta\theta`,
            :math:`dy = d_c (1 - \cos\Delta\theta)/\Delta\theta` (stable as
            :math:`\Delta\theta \to 0`).
        ``"midpoint"``
            Second-order: :math:`d_c` along the mid-step heading,
            :math:`(d_c\cos\frac{\Delta\theta}{2}, d_c\sin\frac{\Delta\theta}{2})`.
        ``"first_order"``
            The papers' first-order (Euler) form: :math:`(d_c, 0)`, i.e. the whole
            step taken along the heading at the start of the step.

        Parameters
        ----------
        d_left, d_right : float or array_like, shape (T,)
            Distance rolled by each wheel, m (e.g. from
            :func:`~navkit.kinematics.ticks_to_distance`); negative when rolling back.
        method : {"arc", "midpoint", "first_order"}
            Integration scheme.

        Returns
        -------
        dx, dy, dtheta : float or ndarray
            Motion in the robot frame at the start of the step (m, m, rad); floats
            for scalar input, arrays of shape (T,) otherwise. Compose with the
            previous pose (e.g. ``Pose2D.compose``) to get the new pose.

        Examples
        --------
        >>> drive = DiffDrive(track=0.5, wheel_radius=0.1)
        >>> dx, dy, dth = drive.odometry_step(0.1, 0.1)
        >>> (dx, dy, dth)
        (0.1, 0.0, 0.0)
        """
        if method not in _METHODS:
            raise ValueError(f"method must be one of {_METHODS}, got {method!r}")
        dl = as_float_array(d_left, "d_left")
        dr = as_float_array(d_right, "d_right")
        if dl.shape != dr.shape or dl.ndim > 1:
            raise ValueError(
                f"d_left and d_right must be scalars or 1-D arrays of equal shape, got "
                f"{dl.shape} and {dr.shape}"
            )
        dc = 0.5 * (dr + dl)
        dth = (dr - dl) / self._track
        if method == "first_order":
            dx, dy = dc, np.zeros_like(dc)
        elif method == "midpoint":
            dx, dy = dc * np.cos(0.5 * dth), dc * np.sin(0.5 * dth)
        elif dl.ndim == 0:
            sx, sy, _ = exp_body(float(dc), 0.0, float(dth), 1.0)
            dx, dy = np.float64(sx), np.float64(sy)
        else:
            out = np.empty((dl.shape[0], 3), dtype=np.float64)
            ones = np.ones_like(dc)
            exp_body_array(dc, np.zeros_like(dc), dth, ones, out)
            dx, dy = out[:, 0], out[:, 1]
        if dl.ndim == 0:
            return float(dx), float(dy), float(dth)
        return np.asarray(dx), np.asarray(dy), np.asarray(dth)

    def __repr__(self) -> str:
        return (
            f"DiffDrive(track={self._track}, left_radius={self._left}, right_radius={self._right})"
        )
