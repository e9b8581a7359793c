"""Simulated proprioceptive sensors and the time-stamped readings of every sensor."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.angles import wrap_float
from navkit._shared.frozen import frozen_setattr, reduce_record, restore_read_only
from navkit._shared.types import IntArray
from navkit._shared.validation import (
    as_float_array,
    bounded_int,
    finite_float,
    positive_float,
    refuse_masked,
)
from navkit.mapping import LaserScan
from navkit.sim._lidar import check_latency, check_rate

__all__ = [
    "Compass",
    "CompassReading",
    "EncoderReading",
    "Imu",
    "ImuReading",
    "Reading",
    "ScanReading",
    "WheelEncoders",
]

_MAX_ANGLE_NOISE = math.pi
_TWO_PI = 2.0 * math.pi
_MAX_RATE_NOISE = 100.0  # rad/s
_MAX_ACCEL_NOISE = 1000.0  # m/s²


#: Largest |angle| (rad) an out-of-range message offers to wrap: beyond it the angle
#: has lost the digits that say where in its turn it is (the bound of heading_deg's yaw).
_WRAP_HINT_MAX = 1e6


def _pi_text(x: float) -> str:
    """``x`` as ``-2π`` .. ``2π`` when it is such a multiple of π, else as ``:g`` shows it."""
    for k, text in ((-2.0, "-2π"), (-1.0, "-π"), (1.0, "π"), (2.0, "2π")):
        if x == k * math.pi:
            return text
    return f"{x:g}"


def _bounded(
    value: object, name: str, low: float, high: float, unit: str, *, periodic: bool = False
) -> float:
    """``value`` as a finite float in ``[low, high]`` (TypeError, ValueError naming ``name``).

    A ``"rad"`` value out of range gets a hint for each reading that would fit:
    a ``periodic`` angle (the same direction a turn later) wrapped to (-π, π],
    and a value whose radians would fit, taken for degrees; the likelier first
    (radians within two turns, degrees beyond), none when neither fits.
    """
    out = finite_float(value, name)
    if not low <= out <= high:
        hints = []
        if unit == "rad" and periodic and abs(out) <= _WRAP_HINT_MAX:
            hints.append(
                f"radians? navkit.geometry.wrap_angle({out!r}) is {wrap_float(out)!r}, "
                "the same direction"
            )
        if unit == "rad" and low <= math.radians(out) <= high:
            degrees = f"degrees? pass math.radians({out!r})"
            if abs(out) <= 2.0 * _TWO_PI:
                hints.append(degrees)
            else:
                hints.insert(0, degrees)
        hint = f" ({'; or '.join(hints)})" if hints else ""
        shown = f"[{_pi_text(low)}, {_pi_text(high)}]" if unit == "rad" else f"[{low:g}, {high:g}]"
        raise ValueError(f"{name} must lie in {shown} {unit}, got {out!r}{hint}")
    return out


@frozen_setattr
@dataclass(frozen=True, slots=True, kw_only=True)
class Compass:
    """A magnetic compass: heading in degrees clockwise from north, 0 to 360.

    The reading is ``degrees(north - yaw + bias + noise) mod 360`` (``bias``
    and ``noise`` in rad, like ``north`` and ``yaw``): 0° when
    the robot faces north, 90° facing east. North is the world direction
    ``north`` (default π/2: +y is north and +x east). The world yaw of a
    reading is ``north + compass_to_yaw(reading)``
    (:func:`navkit.estimation.compass_to_yaw` gives the yaw from north).

    Parameters
    ----------
    noise : float, default 0.0
        Standard deviation of each reading, rad, in [0, π]; independent from
        reading to reading (white), whatever the ``rate``.
    bias : float, default 0.0
        Constant offset of the reading, rad, in [-π, π] (clockwise positive,
        like the reading).
    north : float, default π/2
        World angle of magnetic north, rad, in [-2π, 2π].
    rate : float, default 20.0
        Readings per second, Hz, in (0, 10^4].
    latency : float, default 0.0
        Delivery delay, s, in [0, 10^4].

    Raises
    ------
    TypeError
        A parameter of the wrong type.
    ValueError
        A parameter outside its range (a ``rate`` not > 0 included), NaN or
        inf. An angle out of range is offered each reading that would fit:
        ``north`` or ``bias`` wrapped to (-π, π] (the same direction, up to
        ±1e6 rad) and, where its radians would fit, the value taken for
        degrees.

    Examples
    --------
    >>> Compass(noise=0.01).rate
    20.0
    >>> Compass(north=3 * math.pi)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ValueError: north must lie in [-2π, 2π] rad, got 9.42... (radians? ... is 3.14159..., ...)
    """

    noise: float = 0.0
    bias: float = 0.0
    north: float = math.pi / 2
    rate: float = 20.0
    latency: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(
            self, "noise", _bounded(self.noise, "noise", 0.0, _MAX_ANGLE_NOISE, "rad")
        )
        bias = _bounded(self.bias, "bias", -math.pi, math.pi, "rad", periodic=True)
        object.__setattr__(self, "bias", bias)
        north = _bounded(self.north, "north", -_TWO_PI, _TWO_PI, "rad", periodic=True)
        object.__setattr__(self, "north", north)
        object.__setattr__(self, "rate", check_rate(self.rate))
        object.__setattr__(self, "latency", check_latency(self.latency))

    def heading_deg(self, yaw: float, z: float = 0.0) -> float:
        """The reading for a true ``yaw`` (rad) and a standard-normal draw ``z``.

        Parameters
        ----------
        yaw : float
            True heading, rad, counter-clockwise from the world x axis, within
            ±1e6.
        z : float, default 0.0
            Standard-normal draw scaling :attr:`noise`, within ±1e6; 0 gives the
            noise-free reading (bias included).

        Returns
        -------
        float
            ``(degrees(north - yaw + bias + noise * z)) mod 360``: degrees
            clockwise from north, in [0, 360).

        Raises
        ------
        TypeError, ValueError
            ``yaw`` or ``z`` not finite real numbers within ±1e6.

        Examples
        --------
        >>> Compass().heading_deg(0.0)  # facing +x, east
        90.0
        >>> round(Compass(bias=math.radians(2.0)).heading_deg(math.pi / 2), 9)
        2.0
        """
        yaw = finite_float(yaw, "yaw")
        z = finite_float(z, "z")
        for name, x in (("yaw", yaw), ("z", z)):
            if abs(x) > 1e6:
                raise ValueError(f"{name} must lie within ±1e6, got {x!r}")
        deg = math.degrees(self.north - yaw + self.bias + self.noise * z) % 360.0
        return 0.0 if deg >= 360.0 else deg


@frozen_setattr
@dataclass(frozen=True, slots=True, kw_only=True)
class Imu:
    """A planar IMU: gyro yaw rate and body-frame acceleration, with noise and bias.

    The gyro reads the true yaw rate plus ``gyro_bias`` plus Gaussian noise of
    standard deviation ``gyro_noise``; the accelerometer reads the true
    acceleration of the robot's reference point in the robot frame (gravity
    removed), ``(v̇x - ω vy, v̇y + ω vx)``, plus ``accel_bias`` plus Gaussian
    noise of standard deviation ``accel_noise`` on each axis. The noise is
    drawn independently for every sample and axis (white), with these
    standard deviations per sample whatever the ``rate``: they are not noise
    densities (a datasheet's density ``N``, in rad/s/√Hz or m/s²/√Hz, sampled
    at ``rate`` is about ``N * sqrt(rate)`` per sample). The biases are
    constant (no random walk).

    In a :class:`~navkit.sim.Simulation` the true values are those of the
    physics step ending at the sample, whose body twist is held for the whole
    step (each wheel's mean speed over it, see :class:`~navkit.sim.Robot`):
    the yaw rate is the step's (its heading change over the step's ``dt``,
    the simulation's ``1 / rate``) and ``v̇`` is the change of the held
    velocity from the step before, ``(v_i - v_{i-1}) / dt``, with the step's
    ``ω`` and ``v`` in ``ω × v``. Exact for a held twist, this lags a changing
    one by up to a physics step: wheels ramping from rest at ``α`` read
    ``r α / 2`` at the ramp's first step and again at the step after it ends
    (``r α`` between), and a speed change made at once
    (``max_wheel_acceleration=inf``) reads as ``Δv / dt`` for one step.
    Sampled at every physics step, the yaw rates times ``dt`` sum to the
    heading change, and the ``v̇`` times ``dt`` to the velocity change (to
    rounding).

    With :class:`~navkit.sim.Robot`'s ``wheel_slip`` the held twist itself
    changes at every physics step, by a fresh draw, and the IMU reads those
    changes as the true motion they are: the gyro reads each step's yaw
    rate, whose spread is the same at any physics rate, and the
    accelerometer each step's change of speed over ``dt``, whose spread
    grows in proportion to the physics rate (whatever the IMU's own
    ``rate``), successive readings correlated by -0.5 (0.5 m/s straight
    ahead with ``wheel_slip=0.1``: a forward spread of 3.0 m/s² at 100 Hz,
    30 m/s² at 1 kHz, on top of ``accel_noise``, and not in the variances
    a :class:`~navkit.sim.Simulation` gives its estimator).

    Parameters
    ----------
    gyro_noise : float, default 0.0
        Standard deviation of each gyro sample, rad/s, in [0, 100].
    gyro_bias : float, default 0.0
        rad/s, in [-100, 100].
    accel_noise : float, default 0.0
        Standard deviation of each accelerometer sample on each axis, m/s², in
        [0, 1000].
    accel_bias : float, default 0.0
        m/s², in [-1000, 1000], the same on both axes.
    rate : float, default 100.0
        Hz, in (0, 10^4].
    latency : float, default 0.0
        s, in [0, 10^4].

    Raises
    ------
    TypeError
        A parameter of the wrong type.
    ValueError
        A parameter outside its range (a ``rate`` not > 0 included), NaN or
        inf.

    Examples
    --------
    >>> Imu(gyro_noise=0.01, accel_noise=0.05).rate
    100.0
    """

    gyro_noise: float = 0.0
    gyro_bias: float = 0.0
    accel_noise: float = 0.0
    accel_bias: float = 0.0
    rate: float = 100.0
    latency: float = 0.0

    def __post_init__(self) -> None:
        fields = (
            ("gyro_noise", 0.0, _MAX_RATE_NOISE, "rad/s"),
            ("gyro_bias", -_MAX_RATE_NOISE, _MAX_RATE_NOISE, "rad/s"),
            ("accel_noise", 0.0, _MAX_ACCEL_NOISE, "m/s²"),
            ("accel_bias", -_MAX_ACCEL_NOISE, _MAX_ACCEL_NOISE, "m/s²"),
        )
        for name, low, high, unit in fields:
            object.__setattr__(self, name, _bounded(getattr(self, name), name, low, high, unit))
        object.__setattr__(self, "rate", check_rate(self.rate))
        object.__setattr__(self, "latency", check_latency(self.latency))


@frozen_setattr
@dataclass(frozen=True, slots=True, kw_only=True)
class WheelEncoders:
    """Incremental wheel encoders: quantised, wrapping tick counters.

    Each wheel's counter is ``floor(angle / 2π * ticks_per_rev)`` of the
    wheel's rotation (the motor's, before any slip on the ground): in float64,
    the largest ``k`` whose boundary angle ``(k / ticks_per_rev) * (2 * π)``
    (each operation rounded, ``π = math.pi``) is at most ``angle``, so that
    ``n * 2 * math.pi`` reads exactly ``n * ticks_per_rev`` for whole
    ``ticks_per_rev`` (a simulated run reads the same). Single ticks are
    resolved while ``|angle| / 2π * ticks_per_rev`` is below 2**50. The
    counter is reported modulo ``2**bits`` as an unsigned reading when
    ``bits`` is below 64 (a 64-bit counter reads as a signed int64; decode
    with :func:`navkit.kinematics.tick_delta`). In a
    :class:`~navkit.sim.Simulation` a count beyond the int64 range (2**63
    ticks: 5.8e10 rad at 1e9 ticks a turn, days of wheels at 1e5 rad/s)
    reads as a 64-bit counter wraps, also with ``bits=None``, which
    ``tick_delta(..., bits=64)`` decodes. A wheel that turns half the
    counter range (``2**(bits - 1)`` ticks) or more between two readings
    aliases: the decoders (``tick_delta``, the estimators a
    :class:`~navkit.sim.Simulation` wraps) read the change wrapped, and the
    odometry is silently wrong, as on a real robot. Choose ``bits`` and
    ``rate`` so that ``wheel speed / 2π * ticks_per_rev / rate`` stays well
    below ``2**(bits - 1)`` (1024 ticks a turn read at 50 Hz: wheel speeds
    below about 39 rad/s with 8 bits, 10,000 rad/s with 16).

    Parameters
    ----------
    ticks_per_rev : float, default 1024.0
        Counts per wheel revolution, in [1, 1e9].
    bits : int or None, default 16
        Counter width, 2 to 64; None for counters that never wrap (in a
        simulation, beyond the int64 range they wrap as 64-bit ones).
    rate : float, default 50.0
        Hz, in (0, 10^4].
    latency : float, default 0.0
        s, in [0, 10^4] (the omnidirectional paper measured 0.08 s for
        odometry).

    Raises
    ------
    TypeError
        A parameter of the wrong type.
    ValueError
        A parameter outside its range (a ``rate`` not > 0 included), NaN or
        inf.

    Examples
    --------
    >>> WheelEncoders(ticks_per_rev=2048, bits=16).ticks(np.array([2 * np.pi, -0.001]))
    array([ 2048, 65535])
    """

    ticks_per_rev: float = 1024.0
    bits: int | None = 16
    rate: float = 50.0
    latency: float = 0.0

    def __post_init__(self) -> None:
        tpr = positive_float(self.ticks_per_rev, "ticks_per_rev")
        if not 1.0 <= tpr <= 1e9:
            raise ValueError(f"ticks_per_rev must lie in [1, 1e9], got {tpr}")
        object.__setattr__(self, "ticks_per_rev", tpr)
        if self.bits is not None:
            bits = bounded_int(self.bits, "bits", 2, 64, or_none=True)
            object.__setattr__(self, "bits", bits)
        object.__setattr__(self, "rate", check_rate(self.rate))
        object.__setattr__(self, "latency", check_latency(self.latency))

    def ticks(self, wheel_angles: ArrayLike) -> IntArray:
        """Counter readings (int64) for total wheel rotations ``wheel_angles`` (rad).

        What :attr:`EncoderReading.ticks` holds.

        Parameters
        ----------
        wheel_angles : array_like, shape (N,)
            Total rotation of each wheel since the start, rad, within ±1e9.

        Returns
        -------
        ndarray of int64, shape (N,)
            ``floor(wheel_angles / 2π * ticks_per_rev)`` (by the boundary
            rule of the class docstring), modulo ``2**bits``
            (in ``[0, 2**bits)``) when ``bits`` is below 64, as is otherwise.

        Raises
        ------
        TypeError, ValueError
            ``wheel_angles`` not a 1-D array of finite real numbers within
            ±1e9 rad.

        Examples
        --------
        >>> turns = np.array([0.5, 64.0, -0.0001]) * 2 * math.pi  # half a turn, 64, a bit back
        >>> WheelEncoders(ticks_per_rev=1024, bits=16).ticks(turns)  # 65536 wraps to 0
        array([  512,     0, 65535])
        >>> WheelEncoders(ticks_per_rev=1024, bits=None).ticks(turns)  # never wraps
        array([  512, 65536,    -1])
        """
        wheel_angles = as_float_array(wheel_angles, "wheel_angles", ndim=1)
        worst = float(np.max(np.abs(wheel_angles))) if wheel_angles.size else 0.0
        if worst > 1e9:
            raise ValueError(f"wheel_angles must lie within ±1e9 rad, got |angle| {worst!r}")
        tpr = self.ticks_per_rev
        q = np.floor(wheel_angles * (tpr / _TWO_PI))
        # The product rounds: an angle on a boundary (n whole turns, n * 2 * math.pi) can
        # land just below it. One step to a neighbour fixes that (the error is below a
        # tick while |q| < 2**50); beyond 2**53 q + 1 == q and nothing changes.
        up = ((q + 1.0) / tpr) * _TWO_PI <= wheel_angles
        down = (q / tpr) * _TWO_PI > wheel_angles
        ticks = (q + up - down).astype(np.int64)
        if self.bits is None:
            return ticks
        if self.bits == 64:
            return ticks
        # Modulo 2**bits in two's complement: a mask, as 2**63 does not fit an int64.
        out: IntArray = ticks & np.int64((1 << self.bits) - 1)
        return out

    def counts(self, wheel_angles: ArrayLike) -> IntArray:
        """Deprecated alias of :meth:`ticks` (the name :class:`EncoderReading` uses).

        Parameters
        ----------
        wheel_angles : array_like, shape (N,)
            As for :meth:`ticks`.

        Returns
        -------
        ndarray of int64, shape (N,)
            ``self.ticks(wheel_angles)``.

        Raises
        ------
        TypeError, ValueError
            As :meth:`ticks`.

        Warns
        -----
        DeprecationWarning
            Always.

        Examples
        --------
        >>> WheelEncoders(ticks_per_rev=1024).ticks(np.array([math.pi]))  # not .counts
        array([512])
        """
        warnings.warn(
            "WheelEncoders.counts is deprecated and will be removed in a future release: "
            "use WheelEncoders.ticks",
            DeprecationWarning,
            stacklevel=2,
        )
        return self.ticks(wheel_angles)


def real_float(
    value: object, name: str, *, allow_nan: bool = False, allow_inf: bool = False
) -> float:
    """``value`` as a Python float; NaN / infinities only where allowed (TypeError, ValueError)."""
    if isinstance(value, float) and (
        (allow_nan and math.isnan(value)) or (allow_inf and math.isinf(value))
    ):
        return float(value)
    if isinstance(value, np.floating) and (
        (allow_nan and bool(np.isnan(value))) or (allow_inf and bool(np.isinf(value)))
    ):
        return float(value)
    return finite_float(value, name)


def _python_counts(value: object, raw: np.ndarray[Any, Any]) -> np.ndarray[Any, Any]:
    """Python ints that fit no NumPy integer dtype together, as uint64 modulo 2**64.

    ``raw`` is ``np.asarray(value)``; returned as it is unless ``value`` holds only
    (non-bool) Python or NumPy integers (each element then in the 64-bit counter
    range, ``[-2**63, 2**64)``, ValueError otherwise).
    """
    items = np.array(value, dtype=object)
    if (
        items.ndim != 1
        or items.size == 0
        or not all(
            isinstance(k, (int, np.integer)) and not isinstance(k, (bool, np.bool_)) for k in items
        )
    ):
        return raw
    for k in items:
        if not -(2**63) <= k < 2**64:
            raise ValueError(
                f"ticks must be 64-bit counter readings, in [-2**63, 2**64), got {int(k)}"
            )
    return np.array([int(k) % 2**64 for k in items], dtype=np.uint64)


def _readonly_ints(value: object) -> IntArray:
    if isinstance(value, (str, bytes)):
        raise TypeError(f"ticks must be an integer array, got {type(value).__name__}")
    refuse_masked(value, "ticks")  # np.asarray would read masked ticks as their data
    try:
        raw = np.asarray(value)
    except (ValueError, TypeError) as exc:
        raise TypeError(f"ticks must be an integer array: {exc}") from None
    if raw.dtype.kind in "fO" and not isinstance(value, np.ndarray):
        # Python ints NumPy gives no integer dtype: beyond the int64 range (object),
        # or negative ones beside ones of 2**63 or more (float64, rounded).
        raw = _python_counts(value, raw)
    if raw.dtype.kind not in "iu":
        raise TypeError(f"ticks must be an integer array, got dtype {raw.dtype}")
    if raw.ndim != 1:
        raise ValueError(f"ticks must be one-dimensional, got shape {raw.shape}")
    # Modulo 2**64 (two's complement): uint64 counts of 2**63 or more become
    # count - 2**64, the same 64-bit counter reading (see EncoderReading).
    arr = np.array(raw, dtype=np.int64, copy=True)
    arr.flags.writeable = False
    return arr


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class ScanReading:
    """A LiDAR scan taken at ``stamp`` (s).

    Attributes
    ----------
    stamp : float
        Time the scan was taken, s (finite).
    scan : LaserScan
        The scan, in the sensor frame: beam angles from the x axis of the
        LiDAR's ``mount`` (its pose in the robot frame, see
        :class:`~navkit.sim.Lidar`), which is the robot frame only for the
        default mount. ``scan.to_points(pose @ lidar.mount)`` gives the world
        points at robot ``pose``; consumers that take a scan in the robot
        frame take ``mount=lidar.mount``
        (:func:`~navkit.planning.repulsive_force_from_scan`,
        :meth:`~navkit.control.PotentialFieldController.step`).

    Raises
    ------
    TypeError
        ``stamp`` not a real number, ``scan`` not a LaserScan.
    ValueError
        ``stamp`` NaN or infinite.

    Examples
    --------
    >>> ScanReading(0.1, LaserScan([1.0], angle_min=0.0, angle_increment=0.1,
    ...                            range_min=0.1, range_max=5.0)).stamp
    0.1
    """

    stamp: float
    scan: LaserScan

    def __post_init__(self) -> None:
        object.__setattr__(self, "stamp", finite_float(self.stamp, "stamp"))
        if not isinstance(self.scan, LaserScan):
            raise TypeError(f"scan must be a LaserScan, got {type(self.scan).__name__}")


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class EncoderReading:
    """Raw wheel-encoder counters at ``stamp`` (s), one per wheel.

    Attributes
    ----------
    stamp : float
        Time of the reading, s (finite).
    ticks : ndarray of int64, shape (N,)
        Counter of each wheel (``[left, right]`` for a differential drive), as
        :meth:`WheelEncoders.ticks` gives them; stored as a read-only copy
        (read-only in copies and unpickled readings too). Integers of any
        NumPy dtype, or Python ints in ``[-2**63, 2**64)``, are kept modulo
        ``2**64``: an unsigned 64-bit count of ``2**63`` or more (a driver's
        uint64 counter) is stored as ``count - 2**64``, the same counter bits
        read as int64, which is how a 64-bit counter wraps here anyway (see
        :class:`WheelEncoders`). Decode changes with
        :func:`navkit.kinematics.tick_delta` and the counter's ``bits`` (64
        for such counts), never by subtracting readings.

    Raises
    ------
    TypeError
        ``stamp`` not a real number, ``ticks`` not an integer array (floats
        and booleans included).
    ValueError
        ``stamp`` NaN or infinite, ``ticks`` not one-dimensional, or a Python
        int outside ``[-2**63, 2**64)``.

    Examples
    --------
    >>> EncoderReading(0.02, np.array([10, 12])).ticks.tolist()
    [10, 12]

    A uint64 counter past ``2**63`` reads as int64; its changes are as counted:

    >>> from navkit.kinematics import tick_delta
    >>> before = EncoderReading(0.0, np.array([2**63 - 2], dtype=np.uint64))
    >>> after = EncoderReading(0.02, np.array([2**63 + 3], dtype=np.uint64))
    >>> after.ticks.tolist(), tick_delta(before.ticks, after.ticks, bits=64).tolist()
    ([-9223372036854775805], [5])
    """

    stamp: float
    ticks: IntArray

    if TYPE_CHECKING:
        # The generated ``__init__`` takes integers of any dtype, in a list too
        # (``__post_init__`` converts them); this tells type checkers so, at no runtime cost.
        def __init__(self, stamp: float, ticks: ArrayLike) -> None: ...

    def __post_init__(self) -> None:
        object.__setattr__(self, "stamp", finite_float(self.stamp, "stamp"))
        object.__setattr__(self, "ticks", _readonly_ints(self.ticks))

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, ("ticks",))

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, the arrays read-only again."""
        restore_read_only(self, state, ("ticks",))


@frozen_setattr
@dataclass(frozen=True, slots=True)
class CompassReading:
    """A compass heading at ``stamp`` (s): degrees clockwise from north, in [0, 360).

    Attributes
    ----------
    stamp : float
        Time of the reading, s (finite).
    heading_deg : float
        Heading, degrees clockwise from north (finite; the sensor gives
        [0, 360)). The world yaw is ``north + compass_to_yaw(heading_deg)``
        with the compass's ``north`` (see :class:`Compass`).

    Raises
    ------
    TypeError
        ``stamp`` or ``heading_deg`` not a real number.
    ValueError
        ``stamp`` or ``heading_deg`` NaN or infinite.

    Examples
    --------
    >>> CompassReading(0.05, 90.0).heading_deg
    90.0
    """

    stamp: float
    heading_deg: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "stamp", finite_float(self.stamp, "stamp"))
        object.__setattr__(self, "heading_deg", finite_float(self.heading_deg, "heading_deg"))


@frozen_setattr
@dataclass(frozen=True, slots=True)
class ImuReading:
    """An IMU sample at ``stamp`` (s): gyro yaw rate and body-frame acceleration.

    Attributes
    ----------
    stamp : float
        Time of the sample, s (finite).
    yaw_rate : float
        Gyro yaw rate, rad/s, counter-clockwise positive (finite).
    acceleration_x, acceleration_y : float
        Acceleration in the robot frame (x forward, y left), m/s², gravity
        removed (finite).

    Raises
    ------
    TypeError
        A value not a real number, naming the field.
    ValueError
        A value NaN or infinite, naming the field.

    Examples
    --------
    >>> ImuReading(0.01, 0.2, 0.5, 0.0).yaw_rate
    0.2
    """

    stamp: float
    yaw_rate: float
    acceleration_x: float
    acceleration_y: float

    def __post_init__(self) -> None:
        for name in ("stamp", "yaw_rate", "acceleration_x", "acceleration_y"):
            object.__setattr__(self, name, finite_float(getattr(self, name), name))


Reading = ScanReading | EncoderReading | CompassReading | ImuReading
"""Any time-stamped sensor reading."""
