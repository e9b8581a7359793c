"""Differential-drive kinematics, with unequal wheel radii."""

from __future__ import annotations

from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.dunders import slot_state
from navkit._shared.se2 import exp_body, exp_forward_array
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_bool, as_float_array, finite_float
from navkit.geometry import Pose2D, Twist2D, as_twist, wrap_angle
from navkit.kinematics._ranges import MAX_LENGTH, MIN_LENGTH, in_range

__all__ = ["DiffDrive", "OdometryMethod"]

OdometryMethod = Literal["arc", "midpoint", "first_order"]
"""Integration scheme of one odometry step (see :meth:`DiffDrive.odometry_step`).

``"arc"`` is exact for constant wheel speeds over the step, ``"midpoint"``
moves along the mid-step heading, ``"first_order"`` is the classic Euler form.
"""
_METHODS = ("arc", "midpoint", "first_order")


def _check_method(method: object) -> None:
    if not isinstance(method, str):
        raise TypeError(f"method must be one of {_METHODS}, got {type(method).__name__}")
    if method not in _METHODS:
        raise ValueError(f"method must be one of {_METHODS}, got {method!r}")


def _length(value: object, name: str) -> float:
    return in_range(value, name, MIN_LENGTH, MAX_LENGTH, "m")


def _overflow(name: str, what: str) -> ValueError:
    return ValueError(f"{name}: {what} would overflow float64 (values far too large)")


#: Radii this close (half their difference at most this fraction of their mean) take
#: the twist from the sum and difference of the wheel speeds (see DiffDrive._twist_of).
#: Against exact rationals that is the more accurate formula up to about 1/16 (the
#: component that cancels, a slow turn's or a spot turn's, within 2 ulps of its scale,
#: a spot turn's rate within 2.5; the products' difference up to 13) and the less
#: accurate beyond about 1/8; 1/64 until review 41.
_CLOSE_RADII = 1.0 / 32.0

#: Scale of the retry when a partial result overflowed: 2**-48 is exact, and with
#: lengths in [1e-6, 1e6] (2**±20) no product, sum or quotient of finite inputs
#: this much smaller overflows; only a result beyond the float range stays infinite.
_TINY = 2.0**-48


class DiffDrive:
    r"""Kinematics of a two-wheeled differential drive.

    With wheel angular speeds :math:`\omega_l, \omega_r` (rad/s), wheel radii
    :math:`R_l, R_r` and track width :math:`D` (distance between the wheel contact
    points):

    .. math::  v = \frac{\omega_r R_r + \omega_l R_l}{2}, \qquad
               \omega = \frac{\omega_r R_r - \omega_l R_l}{D}

    and inversely :math:`\omega_r = (v + \omega D/2)/R_r`,
    :math:`\omega_l = (v - \omega D/2)/R_l`. Wheel speeds are always ordered
    ``[left, right]``, as for every drive's :meth:`inverse` and :meth:`forward`.

    An ordinary class with ``__slots__`` rather than a frozen dataclass: its
    constructor takes one common radius or two individual ones and keeps the two
    resolved radii, which a generated ``__init__`` cannot express.

    Parameters
    ----------
    track : float
        Distance between the two wheels' contact points, m, in [1e-6, 1e6].
    wheel_radius : float, optional
        Common wheel radius, m, in [1e-6, 1e6]. Give either this or both
        ``left_radius`` and ``right_radius`` (unequal wheels, e.g. from
        calibration).
    left_radius, right_radius : float, optional
        Individual wheel radii, m, in [1e-6, 1e6].

    Notes
    -----
    All parameters are keyword-only (three floats are too easy to swap).

    Raises
    ------
    TypeError, ValueError
        A parameter that is not a real number or is outside its range, naming
        it. The methods raise ``ValueError`` naming their argument when a
        result would overflow float64 (speeds or distances near ±1.8e308);
        they never return NaN.

    Examples
    --------
    >>> drive = DiffDrive(track=0.3, wheel_radius=0.05)
    >>> drive.forward([10.0, 12.0])
    Twist2D(vx=0.55, vy=0.0, omega=0.333...)
    >>> drive.inverse([0.55, 0.0, 1.0 / 3.0])
    array([10., 12.])
    """

    __slots__ = ("__weakref__", "_left", "_right", "_track")
    __getstate__ = slot_state  # pickle protocols 0 and 1 too

    def __init__(
        self,
        *,
        track: float,
        wheel_radius: float | None = None,
        left_radius: float | None = None,
        right_radius: float | None = None,
    ) -> None:
        self._track = _length(track, "track")
        if wheel_radius is not None:
            if left_radius is not None or right_radius is not None:
                raise ValueError("give either wheel_radius or left_radius/right_radius, not both")
            self._left = self._right = _length(wheel_radius, "wheel_radius")
        else:
            if left_radius is None or right_radius is None:
                raise ValueError("give wheel_radius, or both left_radius and right_radius")
            self._left = _length(left_radius, "left_radius")
            self._right = _length(right_radius, "right_radius")

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

    @property
    def n_wheels(self) -> int:
        """Number of driven wheels: 2 (``[left, right]``)."""
        return 2

    def forward(self, wheel_speeds: ArrayLike) -> Twist2D:
        """Body twist ``(vx, 0, omega)`` from the wheel angular speeds ``[left, right]``, rad/s.

        Parameters
        ----------
        wheel_speeds : array_like, shape (2,)
            ``[omega_left, omega_right]`` in rad/s.

        Returns
        -------
        Twist2D
            The body twist ``(vx, vy, omega)`` in m/s, m/s, rad/s; ``vy`` is
            always 0.

        Raises
        ------
        TypeError, ValueError
            ``wheel_speeds`` not two finite real numbers, or so large that the
            twist would overflow float64.

        Examples
        --------
        >>> drive = DiffDrive(track=0.3, wheel_radius=0.05)
        >>> drive.forward([10.0, 10.0])  # equal speeds: straight ahead
        Twist2D(vx=0.5, vy=0.0, omega=0.0)
        >>> drive.forward([-5.0, 5.0])  # opposite speeds: turning on the spot
        Twist2D(vx=0.0, vy=0.0, omega=1.666...)
        """
        w = as_float_array(wheel_speeds, "wheel_speeds", shape=(2,))
        left, right, radius = float(w[0]), float(w[1]), self._left
        if radius == self._right:  # (as _twist_of, inline: the common case)
            vx, omega = 0.5 * ((right + left) * radius), (right - left) * radius / self._track
        else:
            vx, omega = self._twist_of(left, right)
        if not (vx - vx == 0.0 and omega - omega == 0.0):
            # A sum, product or difference can overflow where the twist does not (a wide
            # track).
            vx, omega = self._twist_of(float(w[0]) * _TINY, float(w[1]) * _TINY)
            with np.errstate(over="ignore"):
                vx, omega = float(np.float64(vx) / _TINY), float(np.float64(omega) / _TINY)
            if not (vx - vx == 0.0 and omega - omega == 0.0):
                raise _overflow("wheel_speeds", "the twist")
        return Twist2D(vx, 0.0, omega)

    def _twist_of(self, left: Any, right: Any) -> tuple[Any, Any]:
        """``(vx, omega)`` of wheel speeds ``left``, ``right`` (floats, or arrays under
        ``np.errstate``: an overflow is an infinity, checked by the caller)."""
        # Not 0.5*(wr*Rr + wl*Rl) and (wr*Rr - wl*Rl)/D: they round each product before
        # a sum that cancels when driving straight (omega) or turning on the spot (vx):
        # a slow turn came out up to 1e-7 off (1e9 ulps). The sum and the difference of
        # the speeds are exact where they cancel (Sterbenz): a few ulps.
        radius = self._left
        if radius == self._right:
            return 0.5 * ((right + left) * radius), (right - left) * radius / self._track
        mean = 0.5 * self._right + 0.5 * self._left
        half_diff = 0.5 * self._right - 0.5 * self._left
        if abs(half_diff) <= _CLOSE_RADII * mean:
            # The same for close radii, with a correction by their difference. Only
            # there: with very unequal radii these terms can be far larger than the
            # products, and so their rounding.
            total = right + left
            diff = right - left
            return (
                0.5 * (total * mean + diff * half_diff),
                (diff * mean + total * half_diff) / self._track,
            )
        wl = left * self._left
        wr = right * self._right
        # 0.5*a + 0.5*b is 0.5*(a + b) bit for bit and cannot overflow.
        return 0.5 * wr + 0.5 * wl, (wr - wl) / self._track

    def _wheels_of(self, vx: Any, omega: Any) -> tuple[Any, Any]:
        """``(left, right)`` wheel speeds of ``vx``, ``omega`` (as :meth:`_twist_of`)."""
        half = 0.5 * omega * self._track
        return (vx - half) / self._left, (vx + half) / self._right

    def inverse(self, twist: Twist2D | ArrayLike, *, ignore_lateral: bool = False) -> FloatArray:
        """Wheel angular speeds ``[omega_left, omega_right]``, rad/s, for ``twist``.

        Parameters
        ----------
        twist : Twist2D or array_like, shape (3,)
            Body twist, or ``[vx, vy, omega]`` (m/s, m/s, rad/s).
        ignore_lateral : bool, default False
            Drop a lateral velocity ``vy`` instead of raising (keyword-only; a
            ``bool``).

        Returns
        -------
        ndarray, shape (2,)
            New array ``[omega_left, omega_right]``, rad/s.

        Raises
        ------
        TypeError
            ``twist`` not a twist, ``ignore_lateral`` not a bool.
        ValueError
            If ``twist.vy != 0`` (a differential drive cannot move sideways) unless
            ``ignore_lateral`` is true, in which case ``vy`` is dropped; or if the
            wheel speeds would overflow float64.

        Examples
        --------
        >>> drive = DiffDrive(track=0.3, wheel_radius=0.05)
        >>> drive.inverse([0.5, 0.0, 0.0])
        array([10., 10.])
        >>> drive.inverse([0.0, 0.0, 1.0])  # turn on the spot at 1 rad/s
        array([-3.,  3.])
        >>> drive.inverse([0.5, 0.1, 0.0], ignore_lateral=True)  # vy dropped
        array([10., 10.])
        """
        tw = as_twist(twist, "twist")
        drop = as_bool(ignore_lateral, "ignore_lateral")
        if tw.vy != 0.0 and not drop:
            raise ValueError(
                f"twist has lateral velocity vy={tw.vy}, which a differential drive cannot "
                "follow; pass ignore_lateral=True to drop it"
            )
        half = 0.5 * tw.omega * self._track  # (as _wheels_of, inline: the common case)
        left = (tw.vx - half) / self._left
        right = (tw.vx + half) / self._right
        if not (left - left == 0.0 and right - right == 0.0):
            # A partial result (omega * track, vx - half) can overflow where a wheel
            # speed does not (large wheels).
            left, right = self._wheels_of(tw.vx * _TINY, tw.omega * _TINY)
            with np.errstate(over="ignore"):
                left, right = float(np.float64(left) / _TINY), float(np.float64(right) / _TINY)
            if not (left - left == 0.0 and right - right == 0.0):
                raise _overflow("twist", "the wheel speeds")
        return np.array([left, right])

    def forward_batch(self, wheel_speeds: ArrayLike) -> FloatArray:
        """Body twists (T, 3) ``[vx, 0, omega]`` from wheel speeds (T, 2) ``[left, right]``.

        Parameters
        ----------
        wheel_speeds : array_like, shape (T, 2)
            Rows ``[omega_left, omega_right]`` in rad/s.

        Returns
        -------
        ndarray, shape (T, 3)
            New array of body twists ``[vx, vy, omega]`` (m/s, m/s, rad/s);
            ``vy`` is always 0.

        Raises
        ------
        TypeError, ValueError
            As :meth:`forward`: speeds not finite real numbers of shape (T, 2),
            or so large that a twist would overflow float64.

        Examples
        --------
        >>> drive = DiffDrive(track=0.3, wheel_radius=0.05)
        >>> drive.forward_batch([[10.0, 10.0], [-5.0, 5.0]]).round(4)
        array([[0.5   , 0.    , 0.    ],
               [0.    , 0.    , 1.6667]])
        """
        w = as_float_array(wheel_speeds, "wheel_speeds", shape=(None, 2))
        with np.errstate(over="ignore", invalid="ignore"):
            vx, omega = self._twist_of(w[:, 0], w[:, 1])
        # Filled column by column (review 28: np.column_stack with a column of zeros
        # peaked at 2 times the result; now 1.7).
        out = np.empty((vx.shape[0], 3))
        out[:, 0] = vx
        out[:, 1] = 0.0
        out[:, 2] = omega
        del vx, omega
        if not np.isfinite(out).all():
            vx, omega = self._twist_of(w[:, 0] * _TINY, w[:, 1] * _TINY)  # as in forward
            with np.errstate(over="ignore"):
                # Only where needed: the rest stay bit for bit those of forward.
                out = np.where(
                    np.isfinite(out), out, np.column_stack((vx, np.zeros_like(vx), omega)) / _TINY
                )
            if not np.isfinite(out).all():
                raise _overflow("wheel_speeds", "the twists")
        return out

    def inverse_batch(self, twists: ArrayLike, *, ignore_lateral: bool = False) -> FloatArray:
        """Wheel speeds (T, 2) ``[omega_left, omega_right]``, rad/s, for twists (T, 3).

        Parameters
        ----------
        twists : array_like, shape (T, 3)
            Rows ``[vx, vy, omega]`` (m/s, m/s, rad/s), robot frame.
        ignore_lateral : bool, default False
            Drop lateral velocities ``vy`` instead of raising (keyword-only; a
            ``bool``).

        Returns
        -------
        ndarray, shape (T, 2)
            New array of rows ``[omega_left, omega_right]``, rad/s.

        Raises
        ------
        TypeError, ValueError
            As :meth:`inverse`: twists not finite real numbers of shape (T, 3),
            a non-zero ``vy`` without ``ignore_lateral``, or wheel speeds that
            would overflow float64.

        Examples
        --------
        >>> drive = DiffDrive(track=0.3, wheel_radius=0.05)
        >>> drive.inverse_batch([[0.5, 0.0, 0.0], [0.0, 0.0, 1.0]])
        array([[10., 10.],
               [-3.,  3.]])
        """
        tw = as_float_array(twists, "twists", shape=(None, 3))
        if not as_bool(ignore_lateral, "ignore_lateral") and np.any(tw[:, 1] != 0.0):
            raise ValueError(
                "twists have non-zero lateral velocity vy, which a differential drive cannot "
                "follow; pass ignore_lateral=True to drop it"
            )
        out = np.empty((tw.shape[0], 2))
        with np.errstate(over="ignore", invalid="ignore"):
            # _wheels_of, written into the result's columns: the same operations, so
            # the same bits (review 28: its arrays and np.column_stack peaked at 2
            # times the result; now 1.5).
            half = np.multiply(tw[:, 2], 0.5)
            half *= self._track
            left = np.subtract(tw[:, 0], half, out=out[:, 0])
            left /= self._left
            right = np.add(tw[:, 0], half, out=out[:, 1])
            right /= self._right
            del half, left, right
        if not np.isfinite(out).all():
            small = self._wheels_of(tw[:, 0] * _TINY, tw[:, 2] * _TINY)  # as in inverse
            with np.errstate(over="ignore"):
                out = np.where(np.isfinite(out), out, np.column_stack(small) / _TINY)
            if not np.isfinite(out).all():
                raise _overflow("twists", "the wheel speeds")
        return out

    def odometry_step(
        self, d_left: float, d_right: float, *, method: OdometryMethod = "arc"
    ) -> Pose2D:
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
        d_left, d_right : float
            Distance rolled by each wheel, m (e.g. from
            :func:`~navkit.kinematics.ticks_to_distance`); negative when rolling
            back. Any finite values.
        method : {"arc", "midpoint", "first_order"}
            Integration scheme (keyword-only).

        Returns
        -------
        Pose2D
            The motion ``(dx, dy, dtheta)`` in the robot frame at the start of the
            step (m, m, rad; ``dtheta`` wrapped to (-π, π]). Compose it with the
            previous pose (``pose.compose(step)``) to get the new pose.
            :meth:`odometry_step_batch` is the array form.

        Raises
        ------
        TypeError, ValueError
            Distances that are not finite real numbers, an unknown ``method``,
            or distances so large that the heading change
            ``(d_right - d_left) / track`` overflows float64 (never a NaN pose).

        Examples
        --------
        >>> drive = DiffDrive(track=0.5, wheel_radius=0.1)
        >>> drive.odometry_step(0.1, 0.1)
        Pose2D(x=0.1, y=0.0, theta=0.0)
        >>> import math  # the right wheel rolls a quarter circle of radius track:
        >>> drive.odometry_step(0.0, 0.5 * math.pi / 2)
        Pose2D(x=0.25, y=0.25, theta=1.5707963267948966)
        """
        _check_method(method)
        dl = finite_float(d_left, "d_left")
        dr = finite_float(d_right, "d_right")
        # 0.5*a + 0.5*b is 0.5*(a + b) bit for bit and cannot overflow.
        dc = 0.5 * dr + 0.5 * dl
        dth = (dr - dl) / self._track
        if dth - dth != 0.0:
            # dr - dl can overflow where the heading change does not (a wide track).
            with np.errstate(over="ignore"):
                dth = float(np.float64(dr * _TINY - dl * _TINY) / self._track / _TINY)
            if dth - dth != 0.0:
                raise _overflow("d_left, d_right", "the heading change (d_right - d_left) / track")
        if method == "first_order":
            dx, dy = dc, 0.0
        elif method == "midpoint":
            dx, dy = dc * float(np.cos(0.5 * dth)), dc * float(np.sin(0.5 * dth))
        else:
            dx, dy, _ = exp_body(dc, 0.0, dth, 1.0)
        return Pose2D(dx, dy, dth)

    def odometry_step_batch(
        self, d_left: ArrayLike, d_right: ArrayLike, *, method: OdometryMethod = "arc"
    ) -> FloatArray:
        """Robot-frame motions of many steps: the array form of :meth:`odometry_step`.

        Parameters
        ----------
        d_left, d_right : array_like, shape (T,)
            Distances rolled by each wheel in each step, m.
        method : {"arc", "midpoint", "first_order"}
            Integration scheme (keyword-only).

        Returns
        -------
        ndarray, shape (T, 3)
            Rows ``[dx, dy, dtheta]``, each the motion of one step in the robot
            frame at its start; row ``i`` equals
            ``odometry_step(d_left[i], d_right[i], method=method).as_array()``.

        Raises
        ------
        TypeError, ValueError
            As :meth:`odometry_step`, or shapes that differ.

        Examples
        --------
        >>> drive = DiffDrive(track=0.5, wheel_radius=0.1)
        >>> drive.odometry_step_batch([0.1, 0.2], [0.1, 0.2])
        array([[0.1, 0. , 0. ],
               [0.2, 0. , 0. ]])
        """
        _check_method(method)
        dl = as_float_array(d_left, "d_left", ndim=1)
        dr = as_float_array(d_right, "d_right", ndim=1)
        if dl.shape != dr.shape:
            raise ValueError(
                f"d_left and d_right must have equal shape, got {dl.shape} and {dr.shape}"
            )
        # Temporaries made in place or dropped early (review 28: the result and up to
        # five arrays of a row's size at once, 2.3 times the result; now 1.7 to 2),
        # the same operations on the same values: the same bits.
        dc = np.multiply(dr, 0.5)
        dc += np.multiply(dl, 0.5)
        with np.errstate(over="ignore", invalid="ignore"):
            dth = np.subtract(dr, dl)
            dth /= self._track
            if not np.isfinite(dth).all():  # as in odometry_step, only where needed
                small = (dr * _TINY - dl * _TINY) / self._track / _TINY
                dth = np.where(np.isfinite(dth), dth, small)
        if not np.isfinite(dth).all():
            raise _overflow("d_left, d_right", "the heading change (d_right - d_left) / track")
        out = np.empty((dl.shape[0], 3), dtype=np.float64)
        if method == "arc":
            exp_forward_array(dc, dth, out)
        elif method == "first_order":
            out[:, 0] = dc
            out[:, 1] = 0.0
        else:
            half = np.multiply(dth, 0.5)
            out[:, 2] = dth  # (wrapped below, in place)
            del dth
            # cos and sin of contiguous arrays, as before: NumPy's SIMD loops for
            # strided ones may round differently.
            turned = np.cos(half)
            np.multiply(dc, turned, out=out[:, 0])
            np.sin(half, out=turned)
            np.multiply(dc, turned, out=out[:, 1])
            del dc, half, turned
            out[:, 2] = wrap_angle(out[:, 2])
            return out
        del dc
        out[:, 2] = wrap_angle(dth)
        return out

    def __repr__(self) -> str:
        return (
            f"{type(self).__name__}(track={self._track}, left_radius={self._left}, "
            f"right_radius={self._right})"
        )
