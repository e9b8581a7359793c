"""Omnidirectional (omni-wheel) drive kinematics."""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.deprecation import renamed_keyword
from navkit._shared.dunders import slot_state
from navkit._shared.frozen import restore_slots
from navkit._shared.products import scaled_product
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array, positive_float
from navkit.geometry import Twist2D, as_twist, wrap_angle
from navkit.kinematics._ranges import MAX_LENGTH, MIN_LENGTH, in_range

__all__ = ["OmniDrive"]

# Condition number above which a wheel layout cannot resolve all three body velocities
# (of the Jacobian with its rotation column divided by the base radius: see __init__).
_MAX_CONDITION = 1e10


def _read_only(arr: FloatArray) -> FloatArray:
    arr.flags.writeable = False
    return arr


def _product(rows: FloatArray, matrix_t: FloatArray, name: str, what: str) -> FloatArray:
    """``rows @ matrix_t``; a ``ValueError`` naming ``name`` if it overflows float64.

    A partial sum can overflow where the result fits (terms that cancel):
    :func:`scaled_product` computes those rows at a scale where none does.
    """
    # Tiny terms underflow to 0 as under NumPy's defaults, whatever the caller's np.seterr
    # (the block is paid for overflow anyway: ignoring underflow too costs nothing).
    with np.errstate(over="ignore", invalid="ignore", under="ignore"):
        out: FloatArray = rows @ matrix_t
    if np.isfinite(out).all():  # the common case: one pass over the result
        return out
    out = scaled_product(rows, matrix_t)
    if not np.isfinite(out).all():
        raise ValueError(f"{name}: {what} would overflow float64 (values far too large)")
    return out


class OmniDrive:
    r"""Kinematics of a robot with N >= 3 omni wheels on a circle.

    Wheel ``i`` sits at angle :math:`\theta_i` (rad, counter-clockwise from the
    robot's x axis) at distance :math:`L` (``base_radius``) from the centre, and
    drives tangentially, along :math:`\theta_i + \pi/2`. Its angular speed for the
    body twist :math:`(v_x, v_y, \omega)` is

    .. math::  \dot\varphi_i = \frac{1}{r}\left(-\sin\theta_i\,v_x + \cos\theta_i\,v_y
               + L\,\omega\right),

    i.e. ``wheel_speeds = jacobian @ [vx, vy, omega]``. :meth:`forward` applies the
    exact inverse of this map (the Moore–Penrose pseudo-inverse, a least-squares
    fit, when N > 3), so ``forward(inverse(t))`` equals ``t`` (up to rounding) for
    every layout.

    Notes
    -----
    The omnidirectional LiDAR robot paper that motivates :meth:`three_wheel`
    states a forward matrix with rows ``r * [cos(θi + π/2), sin(θi + π/2), 1/(3L)]``
    (one column per wheel). That matrix is not the inverse of its own inverse
    kinematics: for three wheels 120° apart the true inverse has
    ``(2r/3)·[cos(θi + π/2), sin(θi + π/2)]`` in the velocity rows, so the paper's
    matrix returns 1.5× the true ``vx`` and ``vy``; and its inverse matrix puts
    ``1/(3L)`` in the rotation column where the lever arm ``L`` belongs. navkit
    implements the geometry above instead; a test shows forward∘inverse is the
    identity.

    An ordinary class with ``__slots__`` rather than a frozen dataclass: it
    computes and keeps its Jacobian and pseudo-inverse once, at construction.

    Parameters
    ----------
    wheel_angles : array_like, shape (N,)
        Mounting angle of each wheel in radians (finite, any turn: 270° and -90°
        are the same wheel), N >= 3.
    wheel_radius : float
        Wheel radius in metres, in [1e-6, 1e6] (keyword-only).
    base_radius : float
        Distance from the robot centre to each wheel contact point, metres, in
        [1e-6, 1e6] (keyword-only).

    Raises
    ------
    TypeError
        Arguments that are not real numbers, naming them.
    ValueError
        Fewer than three wheels, non-finite angles, radii outside their range,
        or a singular layout (e.g. all wheels parallel): the condition number of
        the Jacobian with its rotation column divided by ``base_radius`` (rows
        ``[-sin θi, cos θi, 1]``) above 1e10. The verdict depends on the wheel
        angles only, not on the size of the robot. The
        methods raise ``ValueError`` naming their argument when a result would
        overflow float64 (speeds near ±1.8e308); they never return NaN.

    Examples
    --------
    >>> drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    >>> drive.inverse(Twist2D(1.0, 0.0, 0.0)).round(6)
    array([-10., -10.,  20.])
    >>> drive.forward(drive.inverse([0.3, -0.2, 0.5]))
    Twist2D(vx=0.3..., vy=-0.2..., omega=0.5...)
    >>> OmniDrive(np.radians([45.0, 135.0, 225.0, 315.0]), wheel_radius=0.05, base_radius=0.2)
    OmniDrive(wheel_angles=radians([45, 135, 225, 315]), wheel_radius=0.05, base_radius=0.2)
    """

    __slots__ = (
        "__weakref__",
        "_base_radius",
        "_forward",
        "_jacobian",
        "_wheel_angles",
        "_wheel_radius",
    )
    __getstate__ = slot_state  # pickle protocols 0 and 1 too

    def __init__(self, wheel_angles: ArrayLike, *, wheel_radius: float, base_radius: float) -> None:
        angles = as_float_array(wheel_angles, "wheel_angles", ndim=1)
        if angles.shape[0] < 3:
            raise ValueError(f"wheel_angles needs at least 3 wheels, got {angles.shape[0]}")
        if np.max(np.abs(angles)) > 2 * np.pi and np.all(angles == np.round(angles)):
            # Whole numbers beyond a full turn: a mounting layout in degrees ([30, 150, 270])
            # gives a valid but wrong drive, so say so (radians a tool computed are rarely
            # all whole numbers).
            warnings.warn(
                f"wheel_angles {angles.tolist()} look like degrees (whole numbers beyond 2π): "
                "OmniDrive takes radians, e.g. np.radians([30, 150, 270])",
                UserWarning,
                stacklevel=2,
            )
        self._wheel_radius = in_range(wheel_radius, "wheel_radius", MIN_LENGTH, MAX_LENGTH, "m")
        self._base_radius = in_range(base_radius, "base_radius", MIN_LENGTH, MAX_LENGTH, "m")
        self._wheel_angles = _read_only(angles.copy())
        jac = (
            np.column_stack(
                (-np.sin(angles), np.cos(angles), np.full(angles.shape[0], self._base_radius))
            )
            / self._wheel_radius
        )
        # The layout's verdict, not the Jacobian's: the Jacobian's velocity columns are in
        # 1/m and its rotation column is dimensionless (L / r), so its condition number
        # changes with the robot's size. With omega measured as L * omega (the speed at
        # which turning moves the wheels, m/s, like vx and vy) the test depends on the
        # angles only.
        layout = np.column_stack((-np.sin(angles), np.cos(angles), np.ones(angles.shape[0])))
        if np.linalg.cond(layout) > _MAX_CONDITION:
            raise ValueError(
                "wheel_angles give a singular layout: the wheels cannot resolve vx, vy and "
                "omega independently (e.g. all wheels parallel)"
            )
        self._jacobian = _read_only(jac)
        # jacobian = layout @ diag(1, 1, L) / r with full column rank, so its pseudo-inverse
        # is diag(1, 1, 1/L) @ pinv(layout) * r. Taken from the layout, not the Jacobian:
        # the Jacobian's columns differ in scale by L (up to 1e6 apart), which multiplies
        # its condition number, and pinv's rounding, by as much; beyond 1e15 pinv drops
        # a singular value (an accepted layout at L = 1e6 m turned 1 m/s ahead into
        # 0.05 m/s sideways).
        scale = np.array([1.0, 1.0, self._base_radius])[:, None]
        forward = np.linalg.pinv(layout) / scale * self._wheel_radius
        self._forward = _read_only(np.asarray(forward, dtype=np.float64))

    def __setstate__(
        self, state: dict[str, Any] | tuple[dict[str, Any] | None, dict[str, Any]]
    ) -> None:
        # pickle and copy.deepcopy hand back writable copies of the arrays: the
        # documented read-only attributes of a copy must stay read-only.
        restore_slots(self, state, read_only=("_forward", "_jacobian", "_wheel_angles"))

    @classmethod
    def three_wheel(cls, *, wheel_radius: float, base_radius: float) -> OmniDrive:
        """The Y layout with wheels at 30°, 150° and 270° (120° apart).

        Parameters
        ----------
        wheel_radius, base_radius : float
            Wheel radius and centre-to-wheel distance in metres, each in
            [1e-6, 1e6] (keyword-only).

        Returns
        -------
        OmniDrive
            A drive built from ``radians([30, 150, 270])`` (its :attr:`wheel_angles`
            read them wrapped: 30°, 150° and -90°).

        Raises
        ------
        TypeError
            A radius that is not a real number.
        ValueError
            A radius not finite or outside [1e-6, 1e6].

        Examples
        --------
        >>> OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2).n_wheels
        3
        """
        return cls(
            np.radians([30.0, 150.0, 270.0]), wheel_radius=wheel_radius, base_radius=base_radius
        )

    @property
    def wheel_angles(self) -> FloatArray:
        """Wheel mounting angles, rad, wrapped to (-π, π], shape (N,) (read-only).

        navkit's angles are in (-π, π], so a wheel mounted at 270° reads -π/2. The
        drive keeps the angles as given: its matrices are computed from them (its
        results are the given angles', bit for bit) and its :func:`repr` shows them.

        Examples
        --------
        >>> drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
        >>> np.degrees(drive.wheel_angles).round(6).tolist()
        [30.0, 150.0, -90.0]
        """
        return _read_only(np.asarray(wrap_angle(self._wheel_angles), dtype=np.float64))

    @property
    def wheel_radius(self) -> float:
        """Wheel radius, m."""
        return self._wheel_radius

    @property
    def base_radius(self) -> float:
        """Centre-to-wheel distance (lever arm) L, m."""
        return self._base_radius

    @property
    def n_wheels(self) -> int:
        """Number of wheels N."""
        return int(self._wheel_angles.shape[0])

    @property
    def jacobian(self) -> FloatArray:
        """(N, 3) map from body twist ``[vx, vy, omega]`` to wheel speeds, rad/s (read-only)."""
        return self._jacobian

    @property
    def forward_matrix(self) -> FloatArray:
        """(3, N) exact (pseudo-)inverse of :attr:`jacobian` (read-only)."""
        return self._forward

    def inverse(self, twist: Twist2D | ArrayLike) -> FloatArray:
        """Wheel angular speeds (N,) in rad/s that produce ``twist``.

        Parameters
        ----------
        twist : Twist2D or array_like, shape (3,)
            Body twist, or ``[vx, vy, omega]`` (m/s, m/s, rad/s).

        Returns
        -------
        ndarray, shape (N,)
            New array of wheel speeds, rad/s, in the order of :attr:`wheel_angles`.

        Raises
        ------
        TypeError, ValueError
            ``twist`` not a twist of finite numbers, or one so large that the
            wheel speeds would overflow float64.

        Examples
        --------
        >>> drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
        >>> drive.inverse([0.0, 0.0, 1.0]).round(6)  # turning: L * omega / r each
        array([4., 4., 4.])
        >>> drive.inverse(Twist2D(1.0, 0.0, 0.0)).round(6)
        array([-10., -10.,  20.])
        """
        tw = as_twist(twist, "twist")
        values = tw.as_array()
        with np.errstate(over="ignore", invalid="ignore", under="ignore"):
            speeds: FloatArray = self._jacobian @ values
        if not np.isfinite(speeds).all():
            speeds = _product(values[None, :], self._jacobian.T, "twist", "the wheel speeds")[0]
        return speeds

    def forward(self, wheel_speeds: ArrayLike) -> Twist2D:
        """Body twist from wheel angular speeds (N,) in rad/s (least squares when N > 3).

        Parameters
        ----------
        wheel_speeds : array_like, shape (N,)
            Wheel angular speeds, rad/s, in the order of :attr:`wheel_angles`.

        Returns
        -------
        Twist2D
            ``forward_matrix @ wheel_speeds``: the body twist (m/s, m/s, rad/s),
            the least-squares fit when N > 3.

        Raises
        ------
        TypeError, ValueError
            Speeds that are not N finite real numbers, or so large that the
            twist would overflow float64.

        Examples
        --------
        >>> drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
        >>> drive.forward([4.0, 4.0, 4.0])  # all wheels alike: turning on the spot
        Twist2D(vx=0.0, vy=0.0, omega=1.0)
        >>> drive.forward([-10.0, -10.0, 20.0])  # up to rounding
        Twist2D(vx=1.0, vy=0.0, omega=0.0)
        """
        w = as_float_array(wheel_speeds, "wheel_speeds", shape=(self.n_wheels,))
        with np.errstate(over="ignore", invalid="ignore", under="ignore"):
            twist: FloatArray = self._forward @ w
        if not np.isfinite(twist).all():
            twist = _product(w[None, :], self._forward.T, "wheel_speeds", "the twist")[0]
        vx, vy, omega = twist
        return Twist2D(float(vx), float(vy), float(omega))

    def inverse_batch(self, twists: ArrayLike) -> FloatArray:
        """Wheel speeds (T, N), rad/s, for body twists (T, 3) ``[vx, vy, omega]``.

        Parameters
        ----------
        twists : array_like, shape (T, 3)
            Rows ``[vx, vy, omega]`` (m/s, m/s, rad/s), robot frame.

        Returns
        -------
        ndarray, shape (T, N)
            New array of wheel speeds, rad/s, one row per twist.

        Raises
        ------
        TypeError, ValueError
            As :meth:`inverse`: twists not finite real numbers of shape (T, 3),
            or wheel speeds that would overflow float64.

        Examples
        --------
        >>> drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
        >>> drive.inverse_batch([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]).round(6)
        array([[  4.,   4.,   4.],
               [-10., -10.,  20.]])
        """
        tw = as_float_array(twists, "twists", shape=(None, 3))
        return _product(tw, self._jacobian.T, "twists", "the wheel speeds")

    def forward_batch(self, wheel_speeds: ArrayLike) -> FloatArray:
        """Body twists (T, 3) ``[vx, vy, omega]`` from wheel speeds (T, N), rad/s.

        Parameters
        ----------
        wheel_speeds : array_like, shape (T, N)
            Wheel angular speeds, rad/s, one row per command.

        Returns
        -------
        ndarray, shape (T, 3)
            New array of body twists ``[vx, vy, omega]`` (m/s, m/s, rad/s).

        Raises
        ------
        TypeError, ValueError
            As :meth:`forward`: speeds not finite real numbers of shape (T, N),
            or twists that would overflow float64.

        Examples
        --------
        >>> drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
        >>> drive.forward_batch([[4.0, 4.0, 4.0], [-10.0, -10.0, 20.0]]).round(6) + 0.0
        array([[0., 0., 1.],
               [1., 0., 0.]])
        """
        w = as_float_array(wheel_speeds, "wheel_speeds", shape=(None, self.n_wheels))
        return _product(w, self._forward.T, "wheel_speeds", "the twists")

    def saturate(
        self,
        wheel_speeds: ArrayLike,
        *,
        max_wheel_speed: float | None = None,
        max_speed: float | None = None,
    ) -> FloatArray:
        """Scale wheel speeds so that none exceeds ``max_wheel_speed`` in magnitude.

        All wheels of a command are scaled by the same factor, so the direction of
        motion (the ratios vx : vy : omega) is kept; commands already within the
        limit are returned unchanged.

        Parameters
        ----------
        wheel_speeds : array_like, shape (N,) or (T, N)
            Wheel angular speeds, rad/s.
        max_wheel_speed : float
            Largest allowed wheel speed magnitude, rad/s, finite and at least
            the smallest normal float, about 2.2e-308 (keyword-only, required;
            the name ``sim.Robot`` uses, where ``max_speed`` is a body speed in m/s).

        Returns
        -------
        ndarray
            New array of the input's shape.

        Other Parameters
        ----------------
        max_speed : float, optional
            Deprecated name of `max_wheel_speed`.

        Raises
        ------
        TypeError, ValueError
            ``max_wheel_speed`` missing, not a real number or out of its range
            (a subnormal value such as 5e-324 included), both it and its old
            name given, or ``wheel_speeds`` not finite real numbers of shape
            (N,) or (T, N); each naming the argument.

        Examples
        --------
        >>> drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
        >>> drive.saturate([10.0, -20.0, 5.0], max_wheel_speed=10.0)
        array([ 5. , -10. ,   2.5])
        """
        named = "max_wheel_speed" if max_speed is None else "max_speed"  # as the caller wrote it
        max_wheel_speed = renamed_keyword(
            "max_speed", max_speed, "max_wheel_speed", max_wheel_speed, None
        )
        if max_wheel_speed is None:
            raise TypeError("saturate() missing required keyword-only argument: 'max_wheel_speed'")
        limit = positive_float(max_wheel_speed, named)
        w = as_float_array(wheel_speeds, "wheel_speeds")
        if w.ndim not in (1, 2) or w.shape[-1] != self.n_wheels:
            raise ValueError(
                f"wheel_speeds must have shape ({self.n_wheels},) or (T, {self.n_wheels}), "
                f"got {w.shape}"
            )
        peak = np.max(np.abs(w), axis=-1, keepdims=True)
        over = peak > limit
        # (w / peak) * limit, not w * (limit / peak): |w / peak| <= 1 exactly, so no
        # wheel rounds to above the limit (the fastest lands on it exactly), and a
        # small limit / peak cannot underflow to a zero command.
        # In place on a copy, only where over (review 28: unit, unit * limit and the
        # np.where took 3.4 times the result at the peak; now about 1.4).
        out = w.copy()
        np.divide(w, peak, out=out, where=over)
        np.multiply(out, limit, out=out, where=over)
        return out

    def __repr__(self) -> str:
        # Degrees read best ([30, 150, 270]), but only where they give back the very
        # angles: 6 digits of degrees printed a drive that evaluated to a different one
        # (0.1 rad showed as radians([5.72958])); other angles show exactly, in radians.
        degrees = _degrees_text(self._wheel_angles)
        angles = (
            f"radians([{degrees}])"
            if degrees is not None
            else f"[{', '.join(repr(a) for a in self._wheel_angles.tolist())}]"
        )
        return (
            f"{type(self).__name__}(wheel_angles={angles}, "
            f"wheel_radius={self._wheel_radius}, base_radius={self._base_radius})"
        )


def _degrees_text(angles: FloatArray) -> str | None:
    """``angles`` as degrees of at most 6 decimals that ``np.radians`` maps back bit for bit.

    None when an angle has no such spelling.

    Examples
    --------
    >>> _degrees_text(np.radians([30.0, 150.0, 270.0]))
    '30, 150, 270'
    >>> _degrees_text(np.array([0.1, 2.2, 4.3])) is None
    True
    """
    out = []
    for angle in angles.tolist():
        for decimals in range(7):
            text = f"{np.degrees(angle):.{decimals}f}"
            text = text.rstrip("0").rstrip(".") if "." in text else text
            if text == "-0":
                # eval reads -0 as the integer 0, whose radians are +0.0.
                text = "-0.0"
            back = float(np.radians(float(text)))
            if back == angle and np.signbit(back) == np.signbit(angle):
                out.append(text)
                break
        else:
            return None
    return ", ".join(out)
