"""Dead reckoning: compass-fused omni-wheel odometry and differential-drive encoder odometry."""

from __future__ import annotations

import math
import warnings
from types import MappingProxyType
from typing import Any, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.angles import wrap_float
from navkit._shared.deprecation import renamed_keyword
from navkit._shared.dunders import slot_state
from navkit._shared.frozen import restore_slots
from navkit._shared.se2 import exp_body
from navkit._shared.text import as_text
from navkit._shared.types import FloatArray
from navkit._shared.validation import (
    as_float_array,
    bounded_int,
    finite_float,
    integer_readings,
    is_ndarray,
    positive_float,
)
from navkit.geometry import Pose2D, as_pose, wrap_angle
from navkit.kinematics import DiffDrive, OdometryMethod, OmniDrive, tick_delta, ticks_to_distance

__all__ = ["DiffOdometry", "OmniOdometry"]

_METHODS = ("arc", "midpoint", "first_order")
_INT64_MIN = -(2**63)
_INT64_END = 2**63
# update_batch splits each heading change into a multiple of 2**-24 rad and a remainder
# (see _cumulative_turn).
_TURN_SPLIT = 2.0**24

# A new Pose2D from values known to be finite with theta in (-pi, pi], without
# the validating constructor (one per odometry reading; see _pose).
_object_new = object.__new__
_set_x = Pose2D.__dict__["x"].__set__
_set_y = Pose2D.__dict__["y"].__set__
_set_theta = Pose2D.__dict__["theta"].__set__


_NUMPY_INTS = frozenset(
    (np.int8, np.int16, np.int32, np.int64, np.uint8, np.uint16, np.uint32, np.uint64)
)


def _plain_int(value: object) -> int | None:
    """A NumPy integer scalar or 0-d integer array as a Python int; None for anything else."""
    if type(value) is np.ndarray and value.ndim == 0:
        # A 0-d array (a reading picked with arr[i, ...]) took update_batch's way:
        # 0.1 ms a call instead of 2 us, and its first call compiled a kernel.
        value = value[()]
    return int(value) if type(value) in _NUMPY_INTS else None  # type: ignore[call-overload]


def _pose(x: float, y: float, theta: float) -> Pose2D:
    pose: Pose2D = _object_new(Pose2D)
    _set_x(pose, x)
    _set_y(pose, y)
    _set_theta(pose, theta)
    return pose


def _chain(
    anchor: tuple[float, float],
    travel: tuple[float, float],
    dx: FloatArray,
    dy: FloatArray,
    heading_before: FloatArray,
    positions: FloatArray,
) -> FloatArray:
    """World positions after robot-frame steps (dx, dy) taken at the given headings.

    Writes the (T, 2) positions ``anchor + travelled`` into ``positions`` (which
    may be the memory of ``dx`` and ``dy``: they are read first), overwrites
    ``heading_before`` (the callers' scratch array) and returns
    the (T, 2) world displacements travelled since ``anchor``, the pose last
    set, starting from ``travel``: the rotation of every step is known up
    front, so the sequential composition is a cumulative sum, step by step as
    one :meth:`update` after another adds them (``np.cumsum`` adds in order).

    The steps are summed apart from the anchor, which is added last: added to
    the coordinates themselves, each step would be rounded at their size, with
    one sign for steady steps (1 mm steps at a UTM northing, 5e6 m, drifted by
    1.6 cm per 100 km). From the origin (anchor 0) the positions are the plain
    running sums, bit for bit.
    """
    c = np.cos(heading_before)
    s = np.sin(heading_before, out=heading_before)  # (a scratch array: one fewer)
    moved = np.empty((dx.shape[0] + 1, 2))
    moved[0] = travel
    # In place, with one temporary (review 28: four arrays of the steps' size).
    part = np.multiply(s, dy)
    np.multiply(c, dx, out=moved[1:, 0])
    moved[1:, 0] -= part
    np.multiply(c, dy, out=part)
    np.multiply(s, dx, out=moved[1:, 1])
    moved[1:, 1] += part
    del c, s, part
    np.cumsum(moved, axis=0, out=moved)
    travelled = moved[1:]
    np.add(travelled, np.asarray(anchor), out=positions)
    return travelled


def _cumulative_turn(turn: FloatArray) -> FloatArray:
    """Running sums of the heading changes ``turn`` (each in (-π, π]), up to a multiple of 2π.

    A plain ``np.cumsum`` rounds each partial sum at the size of the running
    total: a robot spinning for 10^6 readings turns 10^4 rad, and its heading
    ends about 2e-7 rad off (stepping reading by reading, wrapped: under
    1e-11 rad, measured). Here each change splits exactly into a multiple of 2**-24 rad
    (truncated towards zero), whose running sums are exact (multiples of
    2**-24 below 2**29 rad) and are wrapped exactly, and a remainder below
    2**-24 rad, whose running sums stay small. The results lie within about
    π + T * 2**-24 rad of zero; for one change it is that change, bit for bit.

    Examples
    --------
    >>> turns = np.full(10**6, 0.0176)  # 2801 turns and a bit
    >>> exact = math.remainder(10**6 * 0.0176, 2 * math.pi)
    >>> float(abs(wrap_angle(np.cumsum(turns)[-1]) - exact)) > 1e-8
    True
    >>> float(abs(wrap_angle(_cumulative_turn(turns)[-1]) - exact)) < 1e-11
    True
    """
    # In place (review 28: six arrays of the turns' size at once, now three).
    coarse = np.multiply(turn, _TURN_SPLIT)
    np.trunc(coarse, out=coarse)
    coarse /= _TURN_SPLIT
    out: FloatArray = np.asarray(wrap_angle(np.cumsum(coarse)))
    np.subtract(turn, coarse, out=coarse)
    out += np.cumsum(coarse, out=coarse)
    return out


#: Largest start coordinate, m, kept apart from the motion (see anchored).
ANCHOR_LIMIT = 1e15


def anchored(start: float) -> float:
    """The part of a start coordinate kept apart from the motion summed since the start.

    The start itself, so that each step is added to the motion since the start
    (rounded at its size) rather than to the coordinate (rounded at the
    coordinate's size, with one sign for steady motion: 1 mm steps at a UTM
    northing, 5e6 m, drifted by 1.6 cm per 100 km). 0 for a start at 0 (the
    coordinate as given, -0.0 included: the plain running sums, bit for bit)
    and beyond ±1e15 m, where the start plus a motion near the float64 limit
    could overflow although neither does (within ±1e15 m the sum rounds to the
    largest float instead).

    Examples
    --------
    >>> anchored(5123456.5), anchored(-0.0), anchored(1e300)
    (5123456.5, 0.0, 0.0)
    """
    return start if 0.0 < abs(start) <= ANCHOR_LIMIT else 0.0


def start_apart(pose: Pose2D) -> tuple[tuple[float, float], tuple[float, float]]:
    """``(anchor, travel)`` of a start pose: its position split by :func:`anchored`.

    Examples
    --------
    >>> start_apart(Pose2D(5e5, 0.0, 1.0))
    ((500000.0, 0.0), (0.0, 0.0))
    """
    ax = anchored(pose.x)
    ay = anchored(pose.y)
    return (ax, ay), (pose.x - ax, pose.y - ay)


def _step_apart(
    anchor: tuple[float, float],
    travel: tuple[float, float],
    c: float,
    s: float,
    dx: float,
    dy: float,
) -> tuple[float, float, tuple[float, float]] | None:
    """One robot-frame step (dx, dy) at heading (cos ``c``, sin ``s``), as :func:`_chain`.

    Returns the world position ``anchor + travel + step`` and the new travel, or
    None when the position is not finite (the caller's fallback raises).
    """
    tx = travel[0] + (c * dx - s * dy)
    ty = travel[1] + (s * dx + c * dy)
    x = anchor[0] + tx
    y = anchor[1] + ty
    if not (x - x == 0.0 and y - y == 0.0):
        return None
    return x, y, (tx, ty)


# Slots that only cache a figure of the drive for the one-step fast paths: left
# out of pickles and copies (which stay as they were) and made again on restore.
_DRIVE_CACHES = frozenset(("_forward_rows", "_track"))


def _odometry_state(obj: DiffOdometry | OmniOdometry) -> object:
    """``__getstate__`` of the odometries: :func:`slot_state` without the drive caches."""
    instance, slots = cast("tuple[Any, dict[str, Any]]", slot_state(obj))
    return instance, {name: value for name, value in slots.items() if name not in _DRIVE_CACHES}


def _restore_odometry(obj: DiffOdometry | OmniOdometry, state: Any) -> None:
    """Restore an odometry's slots; a pickle without ``_anchor`` (older) sums from 0.

    Such a pickle holds the absolute pose only: taken as the steps summed from
    the origin, it carries on exactly as it did when it was saved. The drive
    caches are made again from the drive (pickles never hold them).
    """
    restore_slots(obj, state)
    if not hasattr(obj, "_anchor"):
        pose = obj._pose
        obj._anchor = (0.0, 0.0)
        obj._travel = (pose.x, pose.y)
    if isinstance(obj, OmniOdometry):
        obj._forward_rows = _forward_rows(obj._drive)
    else:
        obj._track = obj._drive.track


def _forward_rows(drive: OmniDrive) -> tuple[list[float], list[float]]:
    """The (forward, left) rows of ``drive.forward_matrix`` as Python floats (the fast path's)."""
    rows = drive.forward_matrix.tolist()
    return rows[0], rows[1]


def _body_steps(inc: FloatArray, forward: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The robot-frame steps (forward, left), each (T,), of (T, N) wheel increments.

    ``inc @ forward[:2].T`` with the products added wheel by wheel, in order, as
    :meth:`OmniOdometry.update` adds them for one step: a matrix product sums in
    an order of the BLAS's choosing, which differs between a (T, N) batch and a
    (1, N) row (OpenBLAS: in the last bit of most rows), so that
    :meth:`OmniOdometry.update` and :meth:`OmniOdometry.update_batch` would not
    agree bit for bit.
    """
    fx = forward[0].tolist()
    fy = forward[1].tolist()
    wheel = inc[:, 0]
    bx = wheel * fx[0]
    by = wheel * fy[0]
    for k in range(1, inc.shape[1]):
        wheel = inc[:, k]
        bx += wheel * fx[k]
        by += wheel * fy[k]
    return bx, by


def _finite_poses(out: FloatArray, name: str) -> None:
    """Raise naming ``name`` if the poses overflowed float64 (inf or NaN)."""
    if not np.all(np.isfinite(out)):
        raise ValueError(
            f"{name}: the odometry overflows float64 (the poses would be infinite); "
            "the odometry is unchanged"
        )


def _batch_deltas(last: int | NDArray[Any], readings: NDArray[Any], bits: int) -> NDArray[Any]:
    """Wrap-aware tick differences of successive ``readings``, the first from ``last``.

    Each pair is differenced by :func:`tick_delta` in the readings' own dtype:
    joining ``last`` (a Python int) to the readings first would promote uint64
    readings to float64.
    """
    first = np.asarray(tick_delta(last, readings[:1], bits=bits))
    rest = np.asarray(tick_delta(readings[:-1], readings[1:], bits=bits))
    return np.concatenate((first, rest))


def _bit_width(value: object, name: str) -> int:
    """``bits`` as an int from 2 to 64 (TypeError for a non-integer, bools included)."""
    bits = bounded_int(value, name, or_none=True)
    if not 2 <= bits <= 64:
        # The wording of kinematics.tick_delta, which takes the same bits.
        raise ValueError(f"{name} must be an integer from 2 to 64, got {bits!r}")
    return bits


class OmniOdometry:
    r"""Omni-wheel odometry whose heading comes from a compass, not from the wheels.

    Implements the omnidirectional-robot paper's equations 5–8: each step's body
    displacement :math:`(\Delta x_b, \Delta y_b)` comes from the wheel rotation
    increments through the drive's forward kinematics, and is rotated into the
    world frame by the compass heading instead of an integrated wheel heading
    (wheel-derived rotation slips; the compass does not drift).

    Two deliberate differences from the paper:

    * the forward kinematics is the exact inverse of the wheel Jacobian
      (:attr:`navkit.kinematics.OmniDrive.forward_matrix`); the paper's forward
      matrix overstates ``vx`` and ``vy`` by 1.5× for three wheels;
    * the displacement is rotated by the mid-step heading
      :math:`\theta_{k-1} + \mathrm{wrap}(\theta_k - \theta_{k-1})/2` (second
      order) rather than by the heading at one end of the step.

    An ordinary class with ``__slots__`` rather than a frozen dataclass: every
    update moves its pose. So it is not thread-safe: one thread at a time may
    call its methods; different odometries may run in different threads at
    once (sharing a drive, which is never changed).

    Far from the origin (a start in UTM coordinates, 5e6 m, where float64
    values lie 9.3e-10 m apart) the steps are summed apart from the start pose
    (``pose``), which is added to the sum: the positions are those of the same
    run from the origin, shifted, to within a few float spacings of the
    coordinates, and :meth:`update` and :meth:`update_batch` agree bit for bit
    however the readings are split. (Steps added to the coordinates themselves would each
    be rounded at the coordinates' size, with one sign for steady motion: 1 mm
    steps at a northing of 5e6 m drifted by 1.6 cm per 100 km.) From the origin
    the positions are the plain running sums of the steps, bit for bit.

    Parameters
    ----------
    drive : OmniDrive
        Wheel layout.
    pose : Pose2D, array_like, shape (3,), or None, default None
        Start pose (keyword-only); None is the origin, ``Pose2D(0, 0, 0)``. Its
        heading should be the compass yaw at the start (e.g. 0 with
        :class:`CompassCalibration`).

    Raises
    ------
    TypeError
        A ``drive`` that is not an :class:`~navkit.kinematics.OmniDrive`; a
        ``pose`` that is not a pose.
    ValueError
        A ``pose`` with NaN or inf, or not three long.

    Examples
    --------
    >>> import numpy as np
    >>> from navkit.geometry import Twist2D
    >>> drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    >>> odo = OmniOdometry(drive)
    >>> step = drive.inverse(Twist2D(1.0, 0.0, 0.0)) * 0.1  # 0.1 s of driving forward
    >>> odo.update(step, np.pi / 2)  # the compass says the robot faces +y
    Pose2D(x=0.07071..., y=0.07071..., theta=1.5707963267948966)
    """

    __slots__ = ("__weakref__", "_anchor", "_drive", "_forward_rows", "_pose", "_travel")
    __getstate__ = _odometry_state  # pickle protocols 0 and 1 too

    def __init__(self, drive: OmniDrive, *, pose: Pose2D | ArrayLike | None = None) -> None:
        if not isinstance(drive, OmniDrive):
            raise TypeError(f"drive must be an OmniDrive, got {type(drive).__name__}")
        self._drive = drive
        # The drive is immutable: its rows are read once, not on every update (~180 ns).
        self._forward_rows = _forward_rows(drive)
        self._pose = Pose2D(0.0, 0.0, 0.0) if pose is None else as_pose(pose, "pose")
        # The position is the start plus the steps summed apart (see _chain): far
        # from the origin, steps added to the coordinates would drift.
        self._anchor, self._travel = start_apart(self._pose)

    def __setstate__(self, state: Any) -> None:
        """Restore a copy or a pickle (one made before the start was kept apart too)."""
        _restore_odometry(self, state)

    @property
    def pose(self) -> Pose2D:
        """Current pose estimate."""
        return self._pose

    @property
    def drive(self) -> OmniDrive:
        """The wheel layout."""
        return self._drive

    def reset(self, pose: Pose2D | ArrayLike | None = None) -> None:
        """Optionally set a new pose, as :meth:`DiffOdometry.reset` does.

        The wheels report increments, so there are no counters to forget: a
        reset without a pose changes nothing (it is accepted so that either
        odometry can be reset the same way). Later steps are summed apart from
        the new pose, as from a start pose given to the constructor: the
        odometry is then the one the constructor builds at that pose, bit for
        bit. Without a pose its steps go on being summed apart from the start
        pose it was last given, so later poses may differ in the last bits
        from those of a new ``OmniOdometry(drive, pose=odo.pose)``; pass
        ``pose=odo.pose`` for the new odometry's numbers.

        Parameters
        ----------
        pose : Pose2D or array_like, shape (3,), optional
            New pose (``[x, y, theta]``, m and rad); None keeps the current one.
            Its heading should be the compass yaw at that moment.

        Raises
        ------
        TypeError, ValueError
            A ``pose`` that is not three finite real numbers; the odometry is
            then unchanged.

        Examples
        --------
        >>> drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
        >>> odo = OmniOdometry(drive)
        >>> step = drive.inverse([1.0, 0.0, 0.0]) * 0.1  # 0.1 s at 1 m/s ahead
        >>> odo.update(step, 0.0).x
        0.1
        >>> odo.reset([5.0, 2.0, 0.0])
        >>> odo.update(step, 0.0)
        Pose2D(x=5.1, y=2.0, theta=0.0)
        """
        if pose is None:
            return
        new_pose = as_pose(pose, "pose")
        anchor, travel = start_apart(new_pose)
        # Plain stores, no call between: an interrupted reset has happened or not.
        self._pose = new_pose
        self._anchor = anchor
        self._travel = travel

    def update(self, wheel_increments: ArrayLike, yaw: float) -> Pose2D:
        """Advance by one step of wheel rotation and return the new pose.

        Parameters
        ----------
        wheel_increments : array_like, shape (N,)
            Rotation of each wheel since the last update, rad.
        yaw : float
            Compass yaw at the end of the step, rad (counter-clockwise, e.g. from
            :func:`compass_to_yaw`).

        Returns
        -------
        Pose2D
            The new pose (m, m, rad; also kept as :attr:`pose`); its heading is
            ``yaw`` wrapped to (-π, π].

        Raises
        ------
        TypeError, ValueError
            Increments or yaw that are not finite real numbers, or increments
            so large that the pose would overflow float64; the odometry is then
            unchanged.

        Examples
        --------
        >>> drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
        >>> odo = OmniOdometry(drive)
        >>> step = drive.inverse([1.0, 0.0, 0.0]) * 0.1  # 0.1 s at 1 m/s ahead
        >>> odo.update(step, 0.0)
        Pose2D(x=0.1, y=0.0, theta=0.0)
        >>> odo.update(step, np.pi / 2)  # turned 90°: moved along the mid-step 45°
        Pose2D(x=0.1707..., y=0.0707..., theta=1.5707963267948966)
        """
        # Fast path (the simulator's call): a float64 array of the right shape and a
        # finite float yaw take update_batch's arithmetic on one step with Python
        # floats (the same IEEE operations, so the same bits: math.cos/sin are the C
        # library's, as NumPy's float64 cos/sin, whose SIMD versions are disabled,
        # numpy#23925; a NumPy with its own, as numpy#29699 proposes, could differ in
        # the last bit, which the fast-path tests would catch); anything else, and a
        # step that overflows, goes the batch way, which checks and raises.
        inc: Any = wheel_increments
        if (
            type(inc) is np.ndarray
            and inc.dtype == np.float64
            and inc.shape == (self._drive.n_wheels,)
            and inc.strides[0] > 0  # a reversed or broadcast view sums in another order
            and type(yaw) is float
            and yaw - yaw == 0.0
        ):
            stepped = self._step(inc, yaw)
            if stepped is not None:
                # Plain stores, no call between (Python delivers a KeyboardInterrupt
                # at calls): an interrupted update has taken the step or not.
                pose, self._travel = stepped
                self._pose = pose
                return pose
        inc = as_float_array(wheel_increments, "wheel_increments", shape=(self._drive.n_wheels,))
        heading = finite_float(yaw, "yaw")
        return Pose2D.from_array(self.update_batch(inc[None, :], [heading])[-1])

    def _step(
        self, inc: FloatArray, yaw: float
    ) -> tuple[Pose2D, tuple[float, float]] | None:
        """The pose and travel after one step of (N,) float64 increments and a yaw, or None.

        None when the increments are not finite or the pose would overflow:
        update_batch then raises.
        """
        # _body_steps for one step: the same products added in the same order, with
        # Python floats (a matrix product sums in an order of the BLAS's choosing,
        # which for a (T, N) batch differs from a (1, N) row's).
        fx, fy = self._forward_rows
        wheels = inc.tolist()
        bx = wheels[0] * fx[0]  # Python floats overflow to inf silently, as NumPy's
        by = wheels[0] * fy[0]
        for k in range(1, len(wheels)):
            bx += wheels[k] * fx[k]
            by += wheels[k] * fy[k]
        # wrap_float, not wrap_angle: yaw is a finite float (checked by update),
        # so is the difference; wrap_angle's own check and call would cost more.
        heading = wrap_float(yaw)
        before = self._pose.theta
        mid = before + 0.5 * wrap_float(heading - before)
        c = math.cos(mid)
        s = math.sin(mid)
        # _chain for one step: the step summed apart from the start, then the start.
        moved = _step_apart(self._anchor, self._travel, c, s, bx, by)
        if moved is None:
            return None
        x, y, travel = moved
        return _pose(x, y, heading), travel

    def update_batch(self, wheel_increments: ArrayLike, yaws: ArrayLike) -> FloatArray:
        """Advance through a log of steps (vectorised) and return every pose.

        Parameters
        ----------
        wheel_increments : array_like, shape (T, N)
            Wheel rotation increments per step, rad.
        yaws : array_like, shape (T,)
            Compass yaw at the end of each step, rad.

        Returns
        -------
        ndarray, shape (T + 1, 3)
            ``[x, y, theta]`` rows (m, m, rad); row 0 is the pose before the
            log (the input rows are increments, as the twists of
            :func:`navkit.geometry.rollout`). The odometry keeps the last pose.

        Raises
        ------
        TypeError, ValueError
            As :meth:`update`.

        Examples
        --------
        >>> drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
        >>> odo = OmniOdometry(drive)
        >>> step = drive.inverse([1.0, 0.0, 0.0]) * 0.1  # 0.1 s at 1 m/s ahead
        >>> odo.update_batch([step, step, step], [0.0, 0.0, np.pi / 2]).round(4) + 0.0
        array([[0.    , 0.    , 0.    ],
               [0.1   , 0.    , 0.    ],
               [0.2   , 0.    , 0.    ],
               [0.2707, 0.0707, 1.5708]])
        >>> odo.pose
        Pose2D(x=0.2707..., y=0.0707..., theta=1.5707963267948966)
        """
        n = self._drive.n_wheels
        inc = as_float_array(wheel_increments, "wheel_increments", shape=(None, n))
        t = inc.shape[0]
        heading = np.asarray(wrap_angle(as_float_array(yaws, "yaws", shape=(t,))))
        with np.errstate(over="ignore", invalid="ignore"):
            bx, by = _body_steps(inc, self._drive.forward_matrix)  # overflow checked below
        previous = np.concatenate(([self._pose.theta], heading[:-1]))
        out = np.empty((t + 1, 3))
        out[0] = self._pose.as_array()
        out[1:, 2] = heading
        # The mid-step headings previous + 0.5 * turn, in place (review 28: the
        # steps' temporaries peaked at 6 times the result; now under 4).
        turn = np.asarray(wrap_angle(np.subtract(heading, previous, out=heading)))
        del heading
        turn *= 0.5
        turn += previous
        del previous
        with np.errstate(over="ignore", invalid="ignore"):
            travelled = _chain(self._anchor, self._travel, bx, by, turn, out[1:, :2])
        _finite_poses(out, "wheel_increments")
        if t:
            pose = Pose2D.from_array(out[-1])
            travel = (float(travelled[-1, 0]), float(travelled[-1, 1]))
            self._pose = pose
            self._travel = travel
        return out

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self._drive!r}, pose={self._pose!r})"


def _counter_range(bits: int | None) -> tuple[int, int, int]:
    """A counter's modulus and the readings the scalar path takes (int64), for ``bits``."""
    width = 64 if bits is None else bits
    return 1 << width, max(-(1 << (width - 1)), _INT64_MIN), min((1 << width) - 1, _INT64_END - 1)


def _metres_per_tick(radius: float, ticks_per_rev: float) -> float:
    """A wheel's metres per tick, computed exactly as ``ticks_to_distance`` computes them."""
    return 2.0 * math.pi * float(radius) / ticks_per_rev


def _old_modulus(odometry: DiffOdometry) -> int:
    return _counter_range(odometry._bits)[0]


def _old_low(odometry: DiffOdometry) -> int:
    return _counter_range(odometry._bits)[1]


def _old_high(odometry: DiffOdometry) -> int:
    return _counter_range(odometry._bits)[2]


def _old_scale_left(odometry: DiffOdometry) -> float:
    return _metres_per_tick(odometry._drive.left_radius, odometry._ticks_per_rev)


def _old_scale_right(odometry: DiffOdometry) -> float:
    return _metres_per_tick(odometry._drive.right_radius, odometry._ticks_per_rev)


class DiffOdometry:
    """Differential-drive pose from successive wheel encoder counts.

    Counter wrap-around is handled with :func:`navkit.kinematics.tick_delta` when
    ``bits`` is given. Each step converts the tick changes to wheel
    distances (each wheel with its own radius) and moves the pose with
    :meth:`navkit.kinematics.DiffDrive.odometry_step_batch`: ``"arc"`` (exact for
    constant wheel speeds over the step), ``"midpoint"`` or ``"first_order"``
    (the classic Euler form).

    An ordinary class with ``__slots__`` rather than a frozen dataclass: every
    reading moves its pose and latches the counters.

    Far from the origin (a start in UTM coordinates, 5e6 m, where float64
    values lie 9.3e-10 m apart) the steps are summed apart from the start pose
    (the last one given to the constructor or :meth:`reset`), which is added
    to the sum: the positions are those of the same run from the origin,
    shifted, to within a few float spacings of the coordinates.
    :meth:`update` and :meth:`update_batch` agree to within rounding however
    the readings are split, not bit for bit: a batch sums the turns where one
    reading at a time wraps each, so the headings may differ in the last bits
    and the positions by as much times the distance travelled (1e5 readings
    over 960 m from the origin: 5.6e-14 rad and 2e-11 m, 219 spacings).
    (Steps added to the coordinates themselves would each be rounded at the
    coordinates' size, with one sign for steady motion: 1 mm steps at a
    northing of 5e6 m drifted by 1.6 cm per 100 km.) From the origin the
    positions are the plain running sums of the steps, bit for bit.

    Parameters
    ----------
    drive : DiffDrive
        Track width and wheel radii.
    ticks_per_rev : float
        Encoder counts per wheel revolution, in [1, 1e12] (as
        :func:`navkit.kinematics.ticks_to_distance`).
    bits : int, optional
        Width of the hardware counters (e.g. 16), an integer from 2 to 64, for
        wrap-around (as ``tick_delta(bits=)`` and ``sim.WheelEncoders(bits=)``);
        None for counters that never wrap (read as 64-bit). Nothing can tell
        a wrap from motion, so the width must be the counter's: a 16-bit
        counter read with None (or 32) takes each wrap, 65535 → 4, as 65,531
        ticks backwards, a silent jump of 20 m on a 5 cm wheel at 1024 ticks
        a turn (with 16: +5 ticks). Between two readings a wheel must turn
        less than half the counter's range (``2**(bits - 1)`` ticks): more is
        read as the shorter change the other way, as
        :func:`navkit.kinematics.tick_delta` does.
    pose : Pose2D, array_like, shape (3,), or None, default None
        Pose at the first reading; None is the origin, ``Pose2D(0, 0, 0)``.
    method : {"arc", "midpoint", "first_order"}, default "arc"
        Integration scheme per step.

    Other Parameters
    ----------------
    encoder_bits : int, optional
        Deprecated name of `bits`.

    Notes
    -----
    Every parameter after ``drive`` is keyword-only.

    An odometry is not thread-safe: one thread at a time may call its methods;
    different odometries may run in different threads at once (sharing a
    drive, which is never changed).

    Raises
    ------
    TypeError, ValueError
        An argument of the wrong type or outside its range, naming it.

    Examples
    --------
    >>> drive = DiffDrive(track=0.5, wheel_radius=0.1)
    >>> odo = DiffOdometry(drive, ticks_per_rev=1000, bits=16)
    >>> odo.update(65000, 65000)  # the first reading only latches the counters
    Pose2D(x=0.0, y=0.0, theta=0.0)
    >>> odo.update(464, 464)  # both counters wrapped: +1000 ticks, one wheel turn
    Pose2D(x=0.6283185307179586, y=0.0, theta=0.0)
    """

    __slots__ = (
        "__weakref__",  # weakref.ref(obj) for callbacks and caches (review 36)
        "_anchor",
        "_bits",
        "_drive",
        "_high",
        "_last",
        "_low",
        "_method",
        "_modulus",
        "_pose",
        "_scale_left",
        "_scale_right",
        "_ticks_per_rev",
        "_track",
        "_travel",
    )
    __getstate__ = _odometry_state  # pickle protocols 0 and 1 too
    # Slots added since a release, for pickles made before (see
    # navkit._shared.frozen.fill_added_fields): the scalar path's counter range and
    # metres per tick (908ac92; an older pickle raised AttributeError at its first
    # update), made from the slots it holds as __init__ makes them. Not annotated:
    # it would read as a slot's type.
    _added_fields = MappingProxyType(
        {
            "_modulus": _old_modulus,
            "_low": _old_low,
            "_high": _old_high,
            "_scale_left": _old_scale_left,
            "_scale_right": _old_scale_right,
        }
    )

    def __init__(
        self,
        drive: DiffDrive,
        *,
        ticks_per_rev: float,
        bits: int | None = None,
        pose: Pose2D | ArrayLike | None = None,
        method: OdometryMethod = "arc",
        encoder_bits: int | None = None,
    ) -> None:
        named = "bits" if encoder_bits is None else "encoder_bits"  # as the caller wrote it
        bits = renamed_keyword("encoder_bits", encoder_bits, "bits", bits, None)
        if not isinstance(drive, DiffDrive):
            raise TypeError(f"drive must be a DiffDrive, got {type(drive).__name__}")
        start = Pose2D(0.0, 0.0, 0.0) if pose is None else as_pose(pose, "pose")
        if not isinstance(method, str):
            raise TypeError(f"method must be one of {_METHODS}, got {type(method).__name__}")
        method = cast(OdometryMethod, as_text(method, "method"))  # checked and kept as plain str
        if method not in _METHODS:
            raise ValueError(f"method must be one of {_METHODS}, got {method!r}")
        bits = None if bits is None else _bit_width(bits, named)
        self._drive = drive
        self._track = drive.track  # the drive is immutable; a slot reads faster than its property
        # ticks_to_distance owns the documented range of ticks_per_rev; checked here once.
        ticks_to_distance(0, ticks_per_rev=ticks_per_rev, wheel_radius=drive.left_radius)
        self._ticks_per_rev = positive_float(ticks_per_rev, "ticks_per_rev")
        self._bits = bits
        self._pose = start
        # The position is the start plus the steps summed apart (see _chain): far
        # from the origin, steps added to the coordinates would drift.
        self._anchor, self._travel = start_apart(start)
        self._method: OdometryMethod = method
        self._last: tuple[int, int] | None = None
        # For the scalar fast path of update(): the counter range, and metres per
        # tick computed exactly as ticks_to_distance computes them.
        self._modulus, self._low, self._high = _counter_range(self._bits)
        self._scale_left = _metres_per_tick(drive.left_radius, self._ticks_per_rev)
        self._scale_right = _metres_per_tick(drive.right_radius, self._ticks_per_rev)

    @property
    def pose(self) -> Pose2D:
        """Current pose estimate."""
        return self._pose

    @property
    def bits(self) -> int | None:
        """Width of the counters it decodes (None: counters that never wrap)."""
        return self._bits

    @property
    def encoder_bits(self) -> int | None:
        """Deprecated alias of :attr:`bits`.

        Examples
        --------
        >>> DiffOdometry(DiffDrive(track=0.5, wheel_radius=0.1), ticks_per_rev=1000, bits=16).bits
        16
        """
        warnings.warn(
            "DiffOdometry.encoder_bits is deprecated and will be removed in a future release: "
            "use DiffOdometry.bits",
            DeprecationWarning,
            stacklevel=2,
        )
        return self._bits

    def reset(self, pose: Pose2D | ArrayLike | None = None) -> None:
        """Forget the latched counters; optionally set a new pose.

        The next :meth:`update` only latches the counters again. With a
        ``pose`` the odometry is the one the constructor builds at that pose
        (same options): later readings give its poses, bit for bit. Without
        one it goes on from where it is, its steps summed as before (apart
        from the start pose it was last given, see the class notes), so its
        later poses are those it would give had it not been reset (but for
        the counters), and may differ in the last bits from those of a new
        ``DiffOdometry(drive, pose=odo.pose)``, which sums from that pose
        (1 ulp after a few steps of 0.3 mm); pass ``pose=odo.pose`` for the
        new odometry's numbers.

        Parameters
        ----------
        pose : Pose2D or array_like, shape (3,), optional
            New pose (``[x, y, theta]``, m and rad); None keeps the current one.

        Raises
        ------
        TypeError, ValueError
            A ``pose`` that is not three finite real numbers.

        Examples
        --------
        >>> odo = DiffOdometry(DiffDrive(track=0.5, wheel_radius=0.1), ticks_per_rev=1000)
        >>> odo.update(0, 0), odo.update(500, 500).x  # half a wheel turn: 0.1π m
        (Pose2D(x=0.0, y=0.0, theta=0.0), 0.314159...)
        >>> odo.reset([0.0, 0.0, 1.0])
        >>> odo.update(9000, 9000)  # counters latched again: no jump
        Pose2D(x=0.0, y=0.0, theta=1.0)
        """
        if pose is None:
            self._last = None
            return
        new_pose = as_pose(pose, "pose")
        anchor, travel = start_apart(new_pose)
        # Plain stores, no call between: an interrupted reset has happened or not.
        self._last = None
        self._pose = new_pose
        self._anchor = anchor
        self._travel = travel

    def update(self, left_ticks: int, right_ticks: int) -> Pose2D:
        """Read both encoder counters and return the new pose.

        The first reading (after construction or :meth:`reset`) only latches the
        counters and returns the current pose.

        Parameters
        ----------
        left_ticks, right_ticks : int
            Raw counter readings (counts) of the left and right encoders
            (wrapping at ``2**bits`` when ``bits`` is set).

        Returns
        -------
        Pose2D
            The new pose (m, m, rad; also kept as :attr:`pose`).

        Raises
        ------
        TypeError
            Readings that are not integers.
        ValueError
            Readings outside the counter's range, or a pose that would overflow
            float64; the odometry is then unchanged.

        Examples
        --------
        >>> odo = DiffOdometry(DiffDrive(track=0.5, wheel_radius=0.1), ticks_per_rev=1000)
        >>> odo.update(0, 0)  # the first reading only latches the counters
        Pose2D(x=0.0, y=0.0, theta=0.0)
        >>> odo.update(500, 500)  # half a turn of each wheel: 0.1π m ahead
        Pose2D(x=0.3141592653589793, y=0.0, theta=0.0)
        >>> odo.update(500, 1000)  # the right wheel alone: an arc to the left
        Pose2D(x=0.4611..., y=0.0477..., theta=0.6283...)
        """
        # Fast path: plain ints within the counter's (and int64's) range take the
        # arithmetic of update_batch on one reading with Python floats (the same
        # IEEE operations, so the same bits; cos/sin as in OmniOdometry.update);
        # anything else goes the batch way.
        left = left_ticks if type(left_ticks) is int else _plain_int(left_ticks)
        right = right_ticks if type(right_ticks) is int else _plain_int(right_ticks)
        if (
            left is not None
            and right is not None
            and self._low <= left <= self._high
            and self._low <= right <= self._high
        ):
            stepped = self._step(left, right)
            if stepped is not None:
                # Plain stores, no call between (Python delivers a KeyboardInterrupt
                # at calls): an interrupted update has taken the reading or not.
                pose, self._travel = stepped
                self._pose = pose
                self._last = (left, right)
                return pose
        # A sequence would reach update_batch as a row of readings and fail there with a
        # message about the shapes of update_batch's arguments.
        given: tuple[tuple[object, str], ...] = (
            (left_ticks, "left_ticks"),
            (right_ticks, "right_ticks"),
        )
        for value, name in given:
            if isinstance(value, (list, tuple)) or (is_ndarray(value) and value.ndim):
                raise TypeError(
                    f"{name} must be one integer counter reading, got {type(value).__name__}"
                )
        return Pose2D.from_array(self.update_batch([left_ticks], [right_ticks])[-1])

    def _step(self, left: int, right: int) -> tuple[Pose2D, tuple[float, float]] | None:
        """The pose and travel after one reading of validated counters, or None on overflow."""
        # The first reading only latches the counters (a zero step, as in update_batch).
        last = (left, right) if self._last is None else self._last
        pose = self._pose
        modulus = self._modulus
        half = modulus >> 1
        # tick_delta: the difference modulo 2**bits, signed.
        dl = (left - last[0]) % modulus
        dr = (right - last[1]) % modulus
        if dl >= half:
            dl -= modulus
        if dr >= half:
            dr -= modulus
        # ticks_to_distance, then DiffDrive.odometry_step_batch.
        d_left = self._scale_left * float(dl)
        d_right = self._scale_right * float(dr)
        dc = 0.5 * d_right + 0.5 * d_left
        dth = (d_right - d_left) / self._track
        if dth - dth != 0.0:  # inf or NaN: update_batch raises
            return None
        if self._method == "first_order":
            dx, dy = dc, 0.0
        elif self._method == "midpoint":
            dx, dy = dc * math.cos(0.5 * dth), dc * math.sin(0.5 * dth)
        else:
            dx, dy, _ = exp_body(dc, 0.0, dth, 1.0)
        # _chain for one step, then the heading.
        before = pose.theta
        c = math.cos(before)
        s = math.sin(before)
        moved = _step_apart(self._anchor, self._travel, c, s, dx, dy)
        if moved is None:
            return None
        x, y, travel = moved
        # dth is finite (checked above) and before + wrap(dth) too: wrap_float directly.
        return _pose(x, y, wrap_float(before + wrap_float(dth))), travel

    def update_batch(self, left_ticks: ArrayLike, right_ticks: ArrayLike) -> FloatArray:
        """Process a log of counter readings (vectorised) and return every pose.

        Parameters
        ----------
        left_ticks, right_ticks : array_like of int, shape (T,)
            Successive raw counter readings (counts).

        Returns
        -------
        ndarray, shape (T, 3)
            ``[x, y, theta]`` (m, m, rad) after each reading: one row per
            reading, as :meth:`PlanarFusion.update_batch` (the pose before the
            log is not a row). The odometry keeps the last pose and counters.

        Raises
        ------
        TypeError
            Readings that are not integers.
        ValueError
            Shapes that differ, readings outside the counter's range, or a
            pose that would overflow float64; the odometry is then unchanged.

        Examples
        --------
        >>> odo = DiffOdometry(DiffDrive(track=0.5, wheel_radius=0.1), ticks_per_rev=1000)
        >>> odo.update_batch([0, 500, 1000], [0, 500, 1000]).round(4)  # row 0 latches
        array([[0.    , 0.    , 0.    ],
               [0.3142, 0.    , 0.    ],
               [0.6283, 0.    , 0.    ]])
        >>> odo.pose  # one wheel turn, 0.2π m
        Pose2D(x=0.6283185307179586, y=0.0, theta=0.0)
        """
        left = integer_readings(left_ticks, "left_ticks")
        right = integer_readings(right_ticks, "right_ticks")
        if left.ndim != 1 or right.shape != left.shape:
            raise ValueError(
                f"left_ticks and right_ticks must be 1-D of equal length, got shapes "
                f"{left.shape} and {right.shape}"
            )
        t = left.shape[0]
        if t == 0:
            return np.empty((0, 3))
        # Counters that never wrap are differenced as 64-bit integers.
        bits = 64 if self._bits is None else self._bits
        for readings, name in ((left, "left_ticks"), (right, "right_ticks")):
            if int(readings.min()) < -(1 << (bits - 1)) or int(readings.max()) >= 1 << bits:
                raise ValueError(f"{name} holds readings outside the range of a {bits}-bit counter")
        last_l, last_r = (left[:1], right[:1]) if self._last is None else self._last
        d_left = np.asarray(
            ticks_to_distance(
                _batch_deltas(last_l, left, bits),
                ticks_per_rev=self._ticks_per_rev,
                wheel_radius=self._drive.left_radius,
            )
        )
        d_right = np.asarray(
            ticks_to_distance(
                _batch_deltas(last_r, right, bits),
                ticks_per_rev=self._ticks_per_rev,
                wheel_radius=self._drive.right_radius,
            )
        )
        steps = self._drive.odometry_step_batch(d_left, d_right, method=self._method)
        del d_left, d_right
        if type(self._drive).odometry_step_batch is not DiffDrive.odometry_step_batch:
            # The poses are written over the steps below: a subclass's may be kept
            # by it or read-only, so only DiffDrive's own fresh array is reused.
            steps = np.array(steps, dtype=np.float64, order="C")
        theta = _cumulative_turn(steps[:, 2])
        theta += self._pose.theta
        before = np.concatenate(([self._pose.theta], theta[:-1]))
        # The poses are written over the steps, a new array of their shape, once
        # read (review 28: a second array and the temporaries peaked at 5.3 times
        # the result; now under 3).
        out = steps
        out[:, 2] = wrap_angle(theta)
        del theta
        with np.errstate(over="ignore", invalid="ignore"):
            travelled = _chain(
                self._anchor, self._travel, steps[:, 0], steps[:, 1], before, out[:, :2]
            )
        _finite_poses(out[:, :2], "left_ticks, right_ticks")
        pose = Pose2D.from_array(out[-1])
        travel = (float(travelled[-1, 0]), float(travelled[-1, 1]))
        last = (int(left[-1]), int(right[-1]))
        # Plain stores, no call between: an interrupted batch has been taken or not.
        self._pose = pose
        self._travel = travel
        self._last = last
        return out

    def __setstate__(self, state: Any) -> None:
        """Restore a copy or a pickle (one made before the start was kept apart too)."""
        _restore_odometry(self, state)

    def __repr__(self) -> str:
        return (
            f"{type(self).__name__}({self._drive!r}, ticks_per_rev={self._ticks_per_rev}, "
            f"bits={self._bits}, method={self._method!r}, pose={self._pose!r})"
        )
