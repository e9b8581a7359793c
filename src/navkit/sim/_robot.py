"""A simulated wheeled robot: drive, wheel imperfections, footprint and sensors."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely
from numpy.typing import ArrayLike
from shapely.geometry import Polygon
from shapely.ops import polylabel

from navkit._shared.frozen import frozen_setattr, reduce_record, restore_read_only
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array, finite_float
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive, OmniDrive
from navkit.sim._lidar import Lidar
from navkit.sim._sensors import Compass, Imu, WheelEncoders
from navkit.sim._world import as_footprint

__all__ = ["Body", "Robot"]

#: Largest wheel speed limit accepted (other than inf), rad/s.
MAX_WHEEL_SPEED = 1e5
#: Largest wheel acceleration limit accepted (other than inf), rad/s².
MAX_WHEEL_ACCELERATION = 1e7
_DEFAULT_ENCODERS = WheelEncoders()


def _kind(value: object) -> str:
    """What ``value`` is, for an error message: a class is named as the class itself."""
    if isinstance(value, type):
        return f"the class {value.__name__} itself"
    return type(value).__name__


def _limit(value: Any, name: str, high: float, unit: str) -> float:
    """A limit in (0, high] or inf (no limit)."""
    if isinstance(value, (float, np.floating)) and value == math.inf:  # float32 inf too
        return math.inf
    out = finite_float(value, name)
    if not 0.0 < out <= high:
        raise ValueError(f"{name} must lie in (0, {high:g}] {unit} or be inf, got {out}")
    return out


@frozen_setattr
@dataclass(frozen=True, slots=True, kw_only=True, eq=False)
class Robot:
    """A wheeled robot for :class:`Simulation`: drive, imperfections, footprint, sensors.

    Commands (body twists) become wheel speeds through the drive's inverse
    kinematics, are scaled down together so that no wheel exceeds
    ``max_wheel_speed`` (the direction of motion is kept), and each wheel
    ramps toward its command within ``max_wheel_acceleration``. The ground
    then moves by each wheel's rotation times its true radius
    (``wheel_radius * (1 + wheel_radius_error)``) less a random slip, through
    the drive's forward kinematics: so odometry computed with the nominal
    drive drifts as on a real robot. Encoders count the wheels' own rotation.
    Within a physics step the body holds one twist, that of the wheels' mean
    speeds over the step, and moves along its exact arc: a held command's
    path, the heading and the wheels' rotations are exact, and a robot
    turning while its wheels ramp strays a little from its exact path, by
    an amount of order ``dt²`` (to 3 rad/s at 20 rad/s² of 5 cm wheels: 1 µm
    after 1.5 s at 100 Hz, 26 µm at 20 Hz).

    Every parameter is keyword-only.

    Parameters
    ----------
    drive : OmniDrive or DiffDrive
        Wheel layout (nominal radii).
    footprint : float, shapely Polygon or array_like (V, 2)
        A radius (m) for a round robot, or a polygon in the robot frame (m,
        3 to 1000 vertices); what collides with the world.
    max_wheel_speed : float, default inf
        Largest wheel speed, rad/s, in (0, 1e5] or inf.
    max_wheel_acceleration : float, default inf
        Largest change of wheel speed, rad/s², in (0, 1e7] or inf.
    wheel_slip : float, default 0.0
        Scale of random slip, in [0, 1]: each physics step each wheel's ground
        speed is its rim speed times ``1 - min(|s|, 1)`` with
        ``s ~ N(0, wheel_slip²)``, drawn anew every step (white, per step:
        not a density). So the robot is slower on average by the mean
        ``|s|``, about ``0.8 * wheel_slip`` of its speed
        (``wheel_slip * sqrt(2 / π)``) at any ``Simulation`` rate, while the
        random part averages over the steps, so that what it does depends on
        the rate. Each step's yaw rate has the same spread at any rate (for a
        differential drive of track ``D`` whose rims move at ``u`` m/s, a
        standard deviation of ``sqrt(2 * (1 - 2 / π)) * wheel_slip * u / D``,
        about ``0.85 * wheel_slip * u / D``): the heading drift after ``T``
        seconds, that times ``sqrt(T / rate)``, is ``sqrt(10)`` times smaller
        at a 10 times higher rate, and the sideways spread after a straight
        drive about the mean speed times that times ``T / sqrt(3)``. An
        :class:`Imu` reads each step's change of speed over ``1 / rate``,
        a spread growing in proportion to the rate (see there). 10 s
        straight at 0.5 m/s on a 0.3 m track with ``wheel_slip=0.1``: 4.60 m
        travelled at 100 Hz and 1 kHz alike, a heading spread of 0.045 rad
        and 0.014 rad, a sideways one of 12 cm and 3.8 cm.
    wheel_radius_error : float or array_like (n_wheels,), default 0.0
        True radius relative to the nominal one, minus 1, in [-0.5, 0.5].
    encoders : WheelEncoders or None, default WheelEncoders()
        Wheel encoders.
    lidar : Lidar, optional
    compass : Compass, optional
    imu : Imu, optional

    Raises
    ------
    TypeError
        A ``drive`` that is not an :class:`~navkit.kinematics.OmniDrive` or a
        :class:`~navkit.kinematics.DiffDrive`; a parameter of the wrong type.
    ValueError
        A parameter outside its range, NaN or inf; a bad ``footprint``.

    Examples
    --------
    >>> lidar = Lidar(noise=None)
    >>> robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2,
    ...               max_wheel_speed=10.0, lidar=lidar)
    >>> robot.n_wheels, lidar.n_beams
    (2, 360)
    """

    drive: OmniDrive | DiffDrive
    # As ``__post_init__`` leaves them: a radius or read-only vertices (V, 2); one
    # read-only error per wheel (the default 0.0 becomes zeros).
    footprint: float | FloatArray
    max_wheel_speed: float = math.inf
    max_wheel_acceleration: float = math.inf
    wheel_slip: float = 0.0
    wheel_radius_error: FloatArray = 0.0  # type: ignore[assignment]
    encoders: WheelEncoders | None = _DEFAULT_ENCODERS
    lidar: Lidar | None = None
    compass: Compass | None = None
    imu: Imu | None = None

    if TYPE_CHECKING:
        # The generated ``__init__`` takes what ``__post_init__`` converts (a shapely
        # polygon, array_like vertices or errors); this signature tells type checkers
        # so, at no runtime cost.
        def __init__(
            self,
            *,
            drive: OmniDrive | DiffDrive,
            footprint: float | Polygon | ArrayLike,
            max_wheel_speed: float = ...,
            max_wheel_acceleration: float = ...,
            wheel_slip: float = ...,
            wheel_radius_error: float | ArrayLike = ...,
            encoders: WheelEncoders | None = ...,
            lidar: Lidar | None = ...,
            compass: Compass | None = ...,
            imu: Imu | None = ...,
        ) -> None: ...

    def __post_init__(self) -> None:
        if not isinstance(self.drive, (OmniDrive, DiffDrive)):
            raise TypeError(
                f"drive must be an OmniDrive or a DiffDrive, got {_kind(self.drive)}: "
                "build one, e.g. DiffDrive(track=0.3, wheel_radius=0.05) or "
                "OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)"
            )
        radius, verts = as_footprint(self.footprint, "footprint")
        verts.flags.writeable = False
        object.__setattr__(self, "footprint", radius if radius else verts)
        object.__setattr__(
            self,
            "max_wheel_speed",
            _limit(self.max_wheel_speed, "max_wheel_speed", MAX_WHEEL_SPEED, "rad/s"),
        )
        object.__setattr__(
            self,
            "max_wheel_acceleration",
            _limit(
                self.max_wheel_acceleration, "max_wheel_acceleration", MAX_WHEEL_ACCELERATION,
                "rad/s²",
            ),
        )  # fmt: skip
        slip = finite_float(self.wheel_slip, "wheel_slip")
        if not 0.0 <= slip <= 1.0:
            raise ValueError(f"wheel_slip must lie in [0, 1], got {slip}")
        object.__setattr__(self, "wheel_slip", slip)
        err = as_float_array(self.wheel_radius_error, "wheel_radius_error")
        if err.ndim == 0:
            err = np.full(self.drive.n_wheels, float(err))
        if err.shape != (self.drive.n_wheels,):
            raise ValueError(
                f"wheel_radius_error must be a scalar or have shape ({self.drive.n_wheels},), "
                f"got {err.shape}"
            )
        if np.any(np.abs(err) > 0.5):
            raise ValueError(
                f"wheel_radius_error must lie in [-0.5, 0.5], got {err.tolist()}: it is the "
                "true radius over the nominal one, minus 1 (0.02 for 2 % larger wheels)"
            )
        err = np.array(err, copy=True)
        err.flags.writeable = False
        object.__setattr__(self, "wheel_radius_error", err)
        for name, kind in (
            ("encoders", WheelEncoders),
            ("lidar", Lidar),
            ("compass", Compass),
            ("imu", Imu),
        ):
            value = getattr(self, name)
            if value is not None and not isinstance(value, kind):
                article = "an" if kind.__name__[0] in "AEIOU" else "a"
                hint = (
                    f": pass an instance, {kind.__name__}()"
                    if isinstance(value, type) and issubclass(value, kind)
                    else ""
                )
                raise TypeError(
                    f"{name} must be {article} {kind.__name__} or None, got {_kind(value)}{hint}"
                )

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, ("footprint", "wheel_radius_error"))

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, the arrays read-only again."""
        restore_read_only(self, state, ("footprint", "wheel_radius_error"))

    @property
    def n_wheels(self) -> int:
        """Number of driven wheels."""
        return int(self.drive.n_wheels)

    @property
    def holonomic(self) -> bool:
        """Whether the robot can move sideways (an omnidirectional drive)."""
        return isinstance(self.drive, OmniDrive)


def _inner_radius(verts: FloatArray) -> float:
    """Radius of a disc inside the simple polygon ``verts`` (V, 2), near the largest, m > 0.

    The distance to the boundary from the polygon's pole of inaccessibility
    (``polylabel``, to a thousandth of its size): exact for that centre, so
    never more than the largest inscribed radius.
    """
    poly = Polygon(verts)
    x0, y0, x1, y1 = poly.bounds
    centre = polylabel(poly, tolerance=1e-3 * max(x1 - x0, y1 - y0))
    radius = float(shapely.distance(poly.exterior, centre))
    if not (radius > 0.0 and poly.contains(centre)):
        # Not expected of a valid polygon of positive area: an interior point's disc.
        radius = float(shapely.distance(poly.exterior, poly.point_on_surface()))
    return radius


class Body:
    """A robot's physical state during a run: pose, twist, wheel speeds and rotations.

    ``state`` is ``[x, y, theta, vx, vy, omega, ax, ay]`` (the layout of
    :mod:`navkit.sim._wheel_kernels`). An ordinary class with ``__slots__``:
    it changes at every physics step.
    """

    __slots__ = (
        "_holonomic",
        "_inverse",
        "_max_speed",
        "angles",
        "command",
        "forward",
        "radius",
        "radius_factor",
        "reach",
        "scratch",
        "state",
        "sweep",
        "verts",
        "wheels",
        "work",
    )

    def __init__(self, robot: Robot, x: float, y: float, theta: float) -> None:
        drive = robot.drive
        n = robot.n_wheels
        eye = np.eye(3)
        if isinstance(drive, DiffDrive):
            inv = drive.inverse_batch(eye, ignore_lateral=True)  # (3, n): twist basis -> wheels
        else:
            inv = drive.inverse_batch(eye)
        # Rows (per wheel) of Python floats: their products overflow to inf silently,
        # where NumPy scalars would warn, and cost less per control step.
        self._inverse: tuple[tuple[float, float, float], ...] = tuple(
            (float(a), float(b), float(c)) for a, b, c in inv.T
        )
        self.forward = np.ascontiguousarray(drive.forward_batch(np.eye(n)).T)  # (3, n)
        self._holonomic = robot.holonomic
        self._max_speed = robot.max_wheel_speed
        assert isinstance(robot.wheel_radius_error, np.ndarray)
        self.radius_factor = np.ascontiguousarray(1.0 + robot.wheel_radius_error)
        self.state = np.zeros(8)
        self.state[:3] = (x, y, theta)
        self.wheels = np.zeros(n)
        self.angles = np.zeros(n)
        self.command = np.zeros(n)
        fp = robot.footprint
        # A disc has no vertices: None, for which the kernels compile only the disc's
        # distance code (and a polygon only the polygon's).
        self.verts: FloatArray | None = None
        self.work: FloatArray | None = None
        self.scratch: FloatArray | None = None
        # How far a step may move the footprint before its sweep is checked (see
        # navkit.sim._segment_kernels): the farthest point of the footprint from the
        # reference point (a turn moves it most; a disc turns onto itself) and the
        # radius of a disc inside the footprint.
        if isinstance(fp, np.ndarray):
            self.radius = 0.0
            self.verts = np.ascontiguousarray(fp, dtype=np.float64)
            self.work = np.empty_like(self.verts)
            self.scratch = np.empty_like(self.verts)
            self.reach = float(np.max(np.hypot(fp[:, 0], fp[:, 1])))
            self.sweep = _inner_radius(fp)
        else:
            self.radius = float(fp)
            self.reach = 0.0
            self.sweep = self.radius

    def set_command(self, twist: Twist2D) -> None:
        """Turn a body twist into wheel-speed commands, scaled together to the speed limit."""
        if not self._holonomic and twist.vy != 0.0:
            raise ValueError(
                f"the controller asked a differential drive for a lateral velocity "
                f"vy={twist.vy}; a differential drive cannot move sideways"
            )
        peak = self._wheel_speeds(twist.vx, twist.vy, twist.omega)
        if peak == math.inf:
            # Wheel speeds beyond float64 (inf, or NaN from inf - inf): those of the
            # twist scaled down to its largest component give the direction.
            if self._max_speed == math.inf:
                raise ValueError(
                    f"the controller's command {twist} needs wheel speeds beyond float64 "
                    "and the robot has no max_wheel_speed to scale it down to"
                )
            scale = max(abs(twist.vx), abs(twist.vy), abs(twist.omega))
            peak = self._wheel_speeds(twist.vx / scale, twist.vy / scale, twist.omega / scale)
            self.command *= self._max_speed / peak
        elif peak > self._max_speed:
            self.command *= self._max_speed / peak

    def _wheel_speeds(self, vx: float, vy: float, omega: float) -> float:
        """Write the wheel speeds of a body twist to ``command``; their largest magnitude.

        inf when one is not finite (NaN included).
        """
        cmd = self.command
        peak = 0.0
        for i, (a, b, c) in enumerate(self._inverse):
            w = a * vx + b * vy + c * omega
            cmd[i] = w
            peak = max(peak, abs(w)) if abs(w) < math.inf else math.inf
        return peak
