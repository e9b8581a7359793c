"""Unit quaternions as ROS writes them, ``(x, y, z, w)``: yaw, matrices and IMU mountings.

Every function is vectorised over leading axes. Quaternions need not be unit
length (they are normalised; float32 rounding in messages is harmless), and a
zero quaternion — ROS 1's default value of an unset orientation — means no
rotation, as in :func:`navkit.mapping.io.grid_from_msg`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, overload

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.deprecation import renamed_keyword
from navkit._shared.frozen import frozen_setattr, reduce_record, restore_read_only
from navkit._shared.products import scaled_product
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array

__all__ = [
    "ImuInBase",
    "imu_to_base",
    "quaternion_to_matrix",
    "quaternion_to_yaw",
    "rpy_to_quaternion",
    "yaw_to_quaternion",
]


def _quaternions(value: ArrayLike, name: str) -> FloatArray:
    """``value`` (..., 4) as unit quaternions; zero rows become the identity ``(0, 0, 0, 1)``."""
    q = as_float_array(value, name)
    if q.ndim == 0 or q.shape[-1] != 4:
        raise ValueError(f"{name} must have shape (..., 4) ordered (x, y, z, w), got {q.shape}")
    # Scale by the largest component first so huge values cannot overflow when squared.
    big = np.max(np.abs(q), axis=-1, keepdims=True)
    zero = big == 0.0
    # A component below 1e-154 of the largest squares to 0 (its share of the norm is
    # below rounding): NumPy's default answer, also under a caller's np.seterr(under=).
    with np.errstate(under="ignore"):
        scaled: FloatArray = q / np.where(zero, 1.0, big)
        norm = np.sqrt(np.sum(scaled * scaled, axis=-1, keepdims=True))
        # In place on this function's own array: fresh copies for the unit
        # quaternions and the identity rows held three at once (memory, batches).
        np.divide(scaled, np.where(zero, 1.0, norm), out=scaled)
    np.copyto(scaled, np.array([0.0, 0.0, 0.0, 1.0]), where=zero)
    return scaled


def _vectors(value: ArrayLike, name: str) -> FloatArray:
    v = as_float_array(value, name)
    if v.ndim == 0 or v.shape[-1] != 3:
        raise ValueError(f"{name} must have shape (..., 3), got {v.shape}")
    return v


def _readonly(arr: FloatArray) -> FloatArray:
    out = np.array(arr, dtype=np.float64, copy=True)
    out.flags.writeable = False
    return out


def _multiply(a: FloatArray, b: FloatArray) -> FloatArray:
    """Hamilton products ``a ⊗ b`` of ``(x, y, z, w)`` quaternions (broadcast)."""
    ax, ay, az, aw = (a[..., i] for i in range(4))
    bx, by, bz, bw = (b[..., i] for i in range(4))
    # Products of two tiny components underflow to 0, as under NumPy's defaults.
    with np.errstate(under="ignore"):
        return np.stack(
            (
                aw * bx + ax * bw + ay * bz - az * by,
                aw * by - ax * bz + ay * bw + az * bx,
                aw * bz + ax * by - ay * bx + az * bw,
                aw * bw - ax * bx - ay * by - az * bz,
            ),
            axis=-1,
        )


def _matrices(q: FloatArray) -> FloatArray:
    """Rotation matrices (..., 3, 3) of unit quaternions (..., 4)."""
    x, y, z, w = (q[..., i] for i in range(4))
    # Each entry written into the result as it is computed: the nine entries, the
    # rows stacked from them and the stacked result were alive at once (memory).
    out = np.empty((*q.shape[:-1], 3, 3), dtype=np.float64)
    # Products of two tiny components underflow to 0, as under NumPy's defaults.
    with np.errstate(under="ignore"):
        out[..., 0, 0] = 1 - 2 * (y * y + z * z)
        out[..., 0, 1] = 2 * (x * y - z * w)
        out[..., 0, 2] = 2 * (x * z + y * w)
        out[..., 1, 0] = 2 * (x * y + z * w)
        out[..., 1, 1] = 1 - 2 * (x * x + z * z)
        out[..., 1, 2] = 2 * (y * z - x * w)
        out[..., 2, 0] = 2 * (x * z - y * w)
        out[..., 2, 1] = 2 * (y * z + x * w)
        out[..., 2, 2] = 1 - 2 * (x * x + y * y)
    return out


@overload
def quaternion_to_yaw(quaternion: Sequence[float]) -> float: ...
@overload
def quaternion_to_yaw(quaternion: Sequence[Sequence[float]]) -> FloatArray: ...
@overload
def quaternion_to_yaw(quaternion: ArrayLike) -> float | FloatArray: ...


def quaternion_to_yaw(quaternion: ArrayLike) -> float | FloatArray:
    """Yaw (heading about z) of quaternions ``(x, y, z, w)``, wrapped to (-π, π].

    The yaw of the ROS roll-pitch-yaw convention ``R = Rz(yaw) Ry(pitch) Rx(roll)``:
    the heading of the rotated x axis projected on the ground plane, what a
    planar filter needs from a 3-D orientation (``nav_msgs/Odometry``,
    ``sensor_msgs/Imu``). Where that axis points straight up or down (pitch
    ±90°) the yaw is undefined and 0 is returned.

    This is tf2's ``tf2::getYaw`` (the same formula, for non-unit quaternions
    too) except within 0.26° of pitch ±90°, where tf2 switches to
    ``±2·atan2(y, x)`` (its gimbal-lock branch, roll taken as 0) and this
    function keeps the heading of the rotated x axis.

    Parameters
    ----------
    quaternion : array_like, shape (..., 4)
        Quaternions ordered ``(x, y, z, w)``, finite; normalised here (a zero
        quaternion means no rotation).

    Returns
    -------
    float or ndarray, shape (...)
        A float for one quaternion, otherwise an array of the leading shape.

    Raises
    ------
    TypeError
        Values that are not real numbers.
    ValueError
        Non-finite values or a last axis that is not 4 long.

    Examples
    --------
    >>> import math
    >>> quaternion_to_yaw([0.0, 0.0, math.sin(0.25), math.cos(0.25)])
    0.5
    >>> quaternion_to_yaw([[0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 0.0]]).round(6)
    array([3.141593, 0.      ])
    """
    # One quaternion as plain floats (a ROS message's fields, one IMU reading, at up
    # to 1 kHz): plain float arithmetic, 1.4 µs against 17 µs the validating way below.
    kind: type[Any] = type(quaternion)
    if kind is list or kind is tuple or kind is np.ndarray:
        values = _plain_quaternion(quaternion)
        if values is not None:
            return _yaw_of_floats(*values)
    q = _quaternions(quaternion, "quaternion")
    x, y, z, w = (q[..., i] for i in range(4))
    # Each argument computed once (twice, they took 14 times the result's memory).
    # Products of tiny components underflow to 0, as under NumPy's defaults.
    # (The yaw too: normal components can give a subnormal one, (1e-160, 1e-160, 0, 1).)
    with np.errstate(under="ignore"):
        sin_part = 2.0 * (w * z + x * y)
        cos_part = 1.0 - 2.0 * (y * y + z * z)
        del q, x, y, z, w
        yaw = np.asarray(np.arctan2(sin_part, cos_part))
        # Pitch ±90°: both arguments are rounding noise; call the yaw 0 rather than noise.
        np.copyto(yaw, 0.0, where=np.hypot(sin_part, cos_part) < 1e-12)
    np.copyto(yaw, math.pi, where=yaw <= -math.pi)
    if yaw.ndim == 0:
        return float(yaw)
    return yaw


def _plain_quaternion(value: Any) -> tuple[float, float, float, float] | None:
    """``value`` as four finite floats when it is one quaternion of plain floats, else None.

    None sends the value the general way, which converts and validates anything
    else (integers, other dtypes, batches) and makes its refusals.
    """
    if type(value) is np.ndarray:
        if value.dtype != np.float64 or value.shape != (4,):
            return None
        # tolist() reads any strides without compiling anything for the layout.
        value = value.tolist()
    elif len(value) != 4:
        return None
    x, y, z, w = value
    # np.float64 is a float subclass: converted, so that its arithmetic cannot follow
    # a caller's np.seterr (the general way ignores underflow).
    for v in (x, y, z, w):
        if (type(v) is not float and type(v) is not np.float64) or not math.isfinite(v):
            return None
    return float(x), float(y), float(z), float(w)


def _yaw_of_floats(x: float, y: float, z: float, w: float) -> float:
    """:func:`quaternion_to_yaw` of one finite quaternion, bit for bit as the array way.

    The same operations in the same order: the largest magnitude scaled out,
    the squares summed left to right (as ``np.sum`` of four values does), and
    NumPy's own ``arctan2`` and ``hypot`` (its ``arctan2`` may be a SIMD one
    that differs from ``math.atan2`` in the last bit).
    """
    big = max(abs(x), abs(y), abs(z), abs(w))
    if big == 0.0:
        return 0.0  # the identity's yaw, as the general way's arctan2(0.0, 1.0)
    x, y, z, w = x / big, y / big, z / big, w / big
    norm = math.sqrt(x * x + y * y + z * z + w * w)
    x, y, z, w = x / norm, y / norm, z / norm, w / norm
    sin_part = 2.0 * (w * z + x * y)
    cos_part = 1.0 - 2.0 * (y * y + z * z)
    # Pitch ±90°: both arguments are rounding noise; call the yaw 0 rather than noise.
    # A hypot is never below its larger argument, so NumPy's is asked only when both
    # are below the threshold (0.7 µs a call).
    if abs(sin_part) < 1e-12 and abs(cos_part) < 1e-12:
        with np.errstate(under="ignore"):  # as the general way's (rare: no cost)
            if float(np.hypot(sin_part, cos_part)) < 1e-12:
                return 0.0
    if sin_part != 0.0 and -_TINY_SIN < sin_part < _TINY_SIN:
        # A yaw that may be subnormal (|cos_part| <= 1): NumPy's default answer and
        # silent, as the general way, whatever the caller's np.seterr. Catching
        # FloatingPointError covered under="raise" only: "warn", "call" and "log"
        # warned (an error under -W error), called or logged where the general way
        # stayed silent.
        with np.errstate(under="ignore"):
            yaw = float(np.arctan2(sin_part, cos_part))
    else:
        yaw = float(np.arctan2(sin_part, cos_part))
    return math.pi if yaw <= -math.pi else yaw


#: Below this |sin_part| a yaw may be subnormal (|cos_part| <= 1 for a unit quaternion,
#: so |yaw| >= |sin_part| / (1 + 2**-50) otherwise): the only arctan2 that can raise
#: NumPy's underflow flag (measured: only subnormal results do).
_TINY_SIN = 2.0**-1000


def yaw_to_quaternion(yaw: ArrayLike) -> FloatArray:
    """Quaternions ``(x, y, z, w)`` of rotations by ``yaw`` about z.

    Parameters
    ----------
    yaw : float or array_like, shape (...)
        Yaw angles, rad, finite.

    Returns
    -------
    ndarray, shape (..., 4)
        ``(0, 0, sin(yaw / 2), cos(yaw / 2))``.

    Raises
    ------
    TypeError
        Values that are not real numbers.
    ValueError
        Non-finite values.

    Examples
    --------
    >>> yaw_to_quaternion(0.0)
    array([0., 0., 0., 1.])
    >>> float(quaternion_to_yaw(yaw_to_quaternion(2.5)))
    2.5
    """
    yaws = as_float_array(yaw, "yaw")
    # Half of a yaw below 4.45e-308 (and its sine) is subnormal: NumPy's default answer
    # whatever the caller's np.seterr.
    with np.errstate(under="ignore"):
        half = 0.5 * yaws
        sines = np.sin(half)
    zero = np.zeros_like(half)
    return np.stack((zero, zero, sines, np.cos(half)), axis=-1)


def rpy_to_quaternion(roll: ArrayLike, pitch: ArrayLike, yaw: ArrayLike) -> FloatArray:
    """Quaternions ``(x, y, z, w)`` of ``R = Rz(yaw) Ry(pitch) Rx(roll)`` (ROS's convention).

    What ``tf``'s static transforms and URDF joints write as ``rpy``: roll about
    x first, then pitch about y, then yaw about z, all about the fixed axes.

    Parameters
    ----------
    roll, pitch, yaw : float or array_like
        Angles, rad, finite; broadcast against each other.

    Returns
    -------
    ndarray, shape (broadcast shape..., 4)

    Raises
    ------
    TypeError
        Values that are not real numbers.
    ValueError
        Non-finite values or shapes that do not broadcast.

    Examples
    --------
    >>> import math
    >>> rpy_to_quaternion(0.0, 0.0, math.pi / 2).round(6)
    array([0.      , 0.      , 0.707107, 0.707107])
    """
    arrays = [as_float_array(v, n) for v, n in ((roll, "roll"), (pitch, "pitch"), (yaw, "yaw"))]
    try:
        r, p, y = np.broadcast_arrays(*arrays)
    except ValueError:
        shapes = ", ".join(str(a.shape) for a in arrays)
        raise ValueError(f"roll, pitch and yaw must broadcast together, got {shapes}") from None
    # Products of two or three tiny sines underflow to 0, as under NumPy's defaults, and
    # half of an angle below 4.45e-308 is subnormal.
    with np.errstate(under="ignore"):
        cr, sr = np.cos(0.5 * r), np.sin(0.5 * r)
        cp, sp = np.cos(0.5 * p), np.sin(0.5 * p)
        cy, sy = np.cos(0.5 * y), np.sin(0.5 * y)
        return np.stack(
            (
                sr * cp * cy - cr * sp * sy,
                cr * sp * cy + sr * cp * sy,
                cr * cp * sy - sr * sp * cy,
                cr * cp * cy + sr * sp * sy,
            ),
            axis=-1,
        )


def quaternion_to_matrix(quaternion: ArrayLike) -> FloatArray:
    """Rotation matrices of quaternions ``(x, y, z, w)``.

    Parameters
    ----------
    quaternion : array_like, shape (..., 4)
        Finite; normalised here (a zero quaternion means no rotation).

    Returns
    -------
    ndarray, shape (..., 3, 3)
        ``R`` with ``v_parent = R @ v_child`` for the frame the quaternion
        orients.

    Raises
    ------
    TypeError
        Values that are not real numbers.
    ValueError
        Non-finite values or a last axis that is not 4 long.

    Examples
    --------
    >>> import math
    >>> quaternion_to_matrix([0.0, 0.0, math.sin(math.pi / 4), math.cos(math.pi / 4)]).round(6)
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    return np.asarray(_matrices(_quaternions(quaternion, "quaternion")), dtype=np.float64)


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class ImuInBase:
    """IMU readings expressed in the robot's base frame (:func:`imu_to_base`).

    Attributes
    ----------
    orientations : ndarray, shape (..., 4)
        Orientation of the base frame in the IMU's world frame, unit quaternions
        ``(x, y, z, w)``.
    angular_velocities : ndarray, shape (..., 3)
        Angular velocity of the base, rad/s, in the base frame.
    linear_accelerations : ndarray, shape (..., 3)
        Linear acceleration, m/s², in the base frame (gravity as the IMU
        measured it; the lever arm of the mounting offset is not removed).

    Raises
    ------
    TypeError
        An array not of real numbers, naming it.
    ValueError
        ``orientations`` not of shape (..., 4), the vectors not of shape
        (..., 3) with the same leading shape, or a value NaN or infinite.

    Notes
    -----
    Every array is a read-only float64 copy. Shapes are checked (the same
    leading shape for all three), values must be finite; orientations are
    normalised (a zero quaternion becomes the identity ``(0, 0, 0, 1)``).

    Examples
    --------
    >>> readings = ImuInBase([0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.1], [0.0, 0.0, 9.8])
    >>> readings.angular_velocities
    array([0. , 0. , 0.1])
    """

    orientations: FloatArray
    angular_velocities: FloatArray
    linear_accelerations: FloatArray

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            orientations: ArrayLike,
            angular_velocities: ArrayLike,
            linear_accelerations: ArrayLike,
        ) -> None: ...

    def __post_init__(self) -> None:
        # Normalised as everywhere in this module (the attribute holds unit quaternions;
        # a zero quaternion, ROS's unset orientation, is no rotation).
        q = _quaternions(self.orientations, "orientations")
        lead = q.shape[:-1]
        w = _vectors(self.angular_velocities, "angular_velocities")
        a = _vectors(self.linear_accelerations, "linear_accelerations")
        for name, arr in (("angular_velocities", w), ("linear_accelerations", a)):
            if arr.shape[:-1] != lead:
                raise ValueError(
                    f"{name} must have shape {(*lead, 3)} to match orientations, got {arr.shape}"
                )
        object.__setattr__(self, "orientations", _readonly(q))
        object.__setattr__(self, "angular_velocities", _readonly(w))
        object.__setattr__(self, "linear_accelerations", _readonly(a))

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, _IMU_ARRAYS)

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, the arrays read-only again."""
        restore_read_only(self, state, _IMU_ARRAYS)


_IMU_ARRAYS = ("orientations", "angular_velocities", "linear_accelerations")


def imu_to_base(
    orientations: ArrayLike,
    angular_velocities: ArrayLike,
    linear_accelerations: ArrayLike,
    *,
    mount: ArrayLike | None = None,
    mounting: ArrayLike | None = None,
) -> ImuInBase:
    """Rotate IMU readings from the IMU's frame into the robot's base frame.

    With ``R_m`` the mounting rotation (the rotation of the ``base_link ->
    imu_link`` transform: ``v_base = R_m v_imu``), vectors become
    ``R_m ω`` and ``R_m a``, and the orientation ``q`` (the IMU frame in the
    world) becomes ``q ⊗ m⁻¹``, the base frame in the world — what
    robot_localization does with an IMU that is not mounted level and facing
    forward. Only the rotation is applied: the lever arm of the mounting
    offset (centripetal and tangential terms) is ignored, as
    robot_localization does.

    Parameters
    ----------
    orientations : array_like, shape (..., 4)
        IMU orientations ``(x, y, z, w)``, finite; normalised (a zero quaternion,
        ROS's unset orientation, is taken as no rotation).
    angular_velocities : array_like, shape (..., 3)
        Angular velocities in the IMU frame, rad/s, same leading shape.
    linear_accelerations : array_like, shape (..., 3)
        Linear accelerations in the IMU frame, m/s², same leading shape.
    mount : array_like, shape (4,)
        Rotation of the IMU frame relative to the base frame, quaternion
        ``(x, y, z, w)`` (non-zero; e.g. ``rpy_to_quaternion(roll, pitch, yaw)``
        of a static transform); keyword-only, required (the name
        ``sim.Lidar(mount=)`` uses for a sensor's pose on the robot).

    Returns
    -------
    ImuInBase
        Orientations, angular velocities and accelerations of the base.

    Other Parameters
    ----------------
    mounting : array_like, optional
        Deprecated name of `mount`.

    Raises
    ------
    TypeError
        Values that are not real numbers, ``mount`` missing, or both it and
        its old name given.
    ValueError
        Non-finite values, wrong or mismatched shapes, a zero ``mount``, or
        readings so large (near ±1.8e308) that a rotated component would
        overflow float64, naming the readings. A component within the float
        range is returned even when a partial sum of it would overflow.

    Examples
    --------
    An IMU mounted yawed by +90° sees the robot's forward acceleration on its
    -y axis and reports a heading 90° larger than the robot's:

    >>> import math
    >>> mount = rpy_to_quaternion(0.0, 0.0, math.pi / 2)
    >>> imu = imu_to_base(yaw_to_quaternion(math.pi / 2), [0.0, 0.0, 0.2], [0.0, -1.0, 9.8],
    ...                   mount=mount)
    >>> imu.linear_accelerations.round(6) + 0.0
    array([1. , 0. , 9.8])
    >>> # float(): an ndarray may hold many quaternions, so type checkers expect float or array.
    >>> round(float(quaternion_to_yaw(imu.orientations)), 6)
    0.0
    """
    named = "mount" if mounting is None else "mounting"  # as the caller wrote it
    mount = renamed_keyword("mounting", mounting, "mount", mount, None)
    if mount is None:
        raise TypeError("imu_to_base() missing required keyword-only argument: 'mount'")
    q = _quaternions(orientations, "orientations")
    w = _vectors(angular_velocities, "angular_velocities")
    a = _vectors(linear_accelerations, "linear_accelerations")
    lead = q.shape[:-1]
    for name, arr in (("angular_velocities", w), ("linear_accelerations", a)):
        if arr.shape[:-1] != lead:
            raise ValueError(
                f"{name} must have shape {(*lead, 3)} to match orientations, got {arr.shape}"
            )
    raw_m = as_float_array(mount, named, shape=(4,))
    if not np.any(raw_m):
        raise ValueError(f"{named} must be a non-zero quaternion (x, y, z, w)")
    m = _quaternions(raw_m, named)
    rot_t = _matrices(m).T
    inverse = m * np.array([-1.0, -1.0, -1.0, 1.0])
    rotated = []
    for name, arr in (("angular_velocities", w), ("linear_accelerations", a)):
        # A rotated vector is as long as the original, but a component of it can lie
        # beyond the float range (up to √3 times the largest one), and a partial sum
        # can overflow where the component does not.
        out = scaled_product(arr, rot_t)
        if not np.isfinite(out).all():
            raise ValueError(
                f"{name}: rotating the readings into the base frame overflows float64 "
                "(values near ±1.8e308)"
            )
        rotated.append(out)
    return ImuInBase(_multiply(q, inverse), rotated[0], rotated[1])
