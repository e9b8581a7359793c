"""The record of a simulation run and its metrics."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np

from navkit._shared.dunders import bounded_repr, record_eq, record_hash
from navkit._shared.frozen import frozen_setattr, reduce_record, restore_read_only
from navkit._shared.text import as_text
from navkit._shared.types import FloatArray
from navkit._shared.validation import (
    as_bool,
    as_float_array,
    bounded_int,
    finite_float,
    kernel_input,
)
from navkit.sim._polyline_distance_kernels import (
    SIMPLE_MAX_SEGMENTS,
    chunk_boxes,
    point_polyline_distances,
    point_polyline_distances_chunked,
)
from navkit.sim._sensors import ScanReading, real_float

__all__ = ["EndReason", "Event", "Metrics", "Trace", "cross_track"]

EndReason = Literal["goal reached", "collision", "timeout", "controller done", "wall-clock timeout"]
"""Why a run ended."""
_END_REASONS = ("goal reached", "collision", "timeout", "controller done", "wall-clock timeout")


def _end_reason(value: object, name: str) -> str:
    """``value``, one of the end reasons, as a plain ``str`` (``TypeError``, ``ValueError``)."""
    if isinstance(value, str):
        # Checked as the plain str stored: a subclass's own == (case-blind, say) let
        # "COLLISION" through, stored as it is, no reason at all.
        text = as_text(value, name)
        if text not in _END_REASONS:
            raise ValueError(f"{name} must be one of {_END_REASONS}, got {text!r}")
        return text
    try:
        equal = value in _END_REASONS
    except ValueError:  # an array of several texts: its == has no single truth value
        equal = True
    if not equal:
        raise ValueError(f"{name} must be one of {_END_REASONS}, got {value!r}")
    return as_text(value, name)  # equal to a reason without being a str: TypeError


@frozen_setattr
@dataclass(frozen=True, slots=True)
class Event:
    """Something that happened during a run.

    Attributes
    ----------
    t : float
        Simulated time, s.
    kind : str
        ``"collision"``, ``"goal reached"``, ``"timeout"``, ``"controller done"``
        or ``"wall-clock timeout"``.
    message : str
        What happened, for people.

    Raises
    ------
    TypeError
        ``t`` not a real number, ``message`` not a str (nor ``kind``, when
        it equals a reason without being a str, or is an array of texts).
    ValueError
        ``t`` NaN or infinite; ``kind`` not one of the reasons above (a
        ``str`` subclass compared as the plain text stored, not with its own
        ``==``).

    Examples
    --------
    >>> Event(1.5, "collision", "the footprint touched an obstacle").kind
    'collision'
    """

    t: float
    kind: EndReason
    message: str

    if TYPE_CHECKING:
        # Built from any str: the constructor checks it is one of EndReason.
        def __init__(self, t: float, kind: str, message: str) -> None: ...

    def __post_init__(self) -> None:
        object.__setattr__(self, "t", finite_float(self.t, "t"))
        # Plain str: an np.str_ printed as np.str_('collision') in the record's repr.
        object.__setattr__(self, "kind", _end_reason(self.kind, "kind"))
        object.__setattr__(self, "message", as_text(self.message, "message"))


@frozen_setattr
@dataclass(frozen=True, slots=True)
class Metrics:
    """Summary of a run (NaN where a figure does not apply).

    Attributes
    ----------
    reached : bool
        Whether the robot's true pose met the goal condition at some step.
    reason : str
        Why the run ended (an :data:`EndReason`); with ``"timeout"`` the run hit
        its ``duration``, with ``"wall-clock timeout"`` its ``wall_timeout``.
    duration : float
        Simulated time of the run, s.
    time_to_goal : float
        First time the goal condition held, s, at most ``duration`` (NaN if
        never: exactly when ``reached`` is False).
    final_error : float
        Distance from the final true position to the goal, m (NaN without goal).
    final_error_estimated : float
        Distance from the final estimated position to the goal, m (NaN without
        an estimator or a goal).
    estimate_error : float
        Distance between the final estimated and true positions, m (NaN
        without an estimator).
    cross_track_mean, cross_track_max : float
        Mean and largest distance of the recorded true positions to the
        reference path, m (NaN without one).
    min_clearance : float
        Smallest distance between the footprint and any obstacle over the run,
        m (0 after a collision; ``inf`` in an empty world).
    collisions : int
        Number of collisions.
    distance : float
        Length of the path the robot travelled, m.

    Raises
    ------
    TypeError, ValueError
        A value of the wrong type or out of its range, naming the field: every
        time and distance is >= 0 (NaN only where it says so), ``duration``
        and ``distance`` are finite, ``time_to_goal`` disagrees with
        ``reached`` or exceeds ``duration``.

    Examples
    --------
    >>> Metrics(True, "goal reached", 10.0, 9.5, 0.04, 0.06, 0.02, 0.01, 0.05,
    ...         0.3, 0, 4.2).reached
    True
    """

    reached: bool
    # As ``__post_init__`` leaves it: one of the end reasons (any str is taken, and
    # checked, by the declared ``__init__`` below).
    reason: EndReason
    duration: float
    time_to_goal: float
    final_error: float
    final_error_estimated: float
    estimate_error: float
    cross_track_mean: float
    cross_track_max: float
    min_clearance: float
    collisions: int
    distance: float

    if TYPE_CHECKING:

        def __init__(
            self,
            reached: bool,
            reason: str,
            duration: float,
            time_to_goal: float,
            final_error: float,
            final_error_estimated: float,
            estimate_error: float,
            cross_track_mean: float,
            cross_track_max: float,
            min_clearance: float,
            collisions: int,
            distance: float,
        ) -> None: ...

    # NaN figures ("does not apply") equal in a run and its rerun, copy or pickle.
    def __eq__(self, other: object) -> bool:
        # A method, not ``__eq__ = record_eq``: type checkers then see object's signature.
        return record_eq(self, other)

    __hash__ = record_hash

    def __post_init__(self) -> None:
        object.__setattr__(self, "reached", as_bool(self.reached, "reached"))
        object.__setattr__(self, "reason", _end_reason(self.reason, "reason"))
        # Every figure is a time since the run's start or a distance: none can be
        # negative (a negative one is a sign or an origin mixed up by its maker).
        for name in ("duration", "distance"):
            value = finite_float(getattr(self, name), name)
            if value < 0.0:
                raise ValueError(f"{name} must be >= 0, got {value!r}")
            object.__setattr__(self, name, value)
        for name in (
            "time_to_goal", "final_error", "final_error_estimated", "estimate_error",
            "cross_track_mean", "cross_track_max",
        ):  # fmt: skip
            value = real_float(getattr(self, name), name, allow_nan=True)
            if value < 0.0:
                raise ValueError(f"{name} must be >= 0 (or NaN: does not apply), got {value!r}")
            object.__setattr__(self, name, value)
        # Both say whether the goal was reached, and the goal is reached within the run.
        time_to_goal = self.time_to_goal
        if self.reached == math.isnan(time_to_goal):
            raise ValueError(
                f"time_to_goal must be NaN exactly when reached is False, got reached="
                f"{self.reached} and time_to_goal={time_to_goal!r}"
            )
        if time_to_goal > self.duration:
            raise ValueError(
                f"time_to_goal must be <= duration, got {time_to_goal!r} > {self.duration!r}"
            )
        clearance = real_float(self.min_clearance, "min_clearance", allow_inf=True)
        if clearance < 0.0:
            raise ValueError(f"min_clearance must be >= 0 (or inf), got {clearance}")
        object.__setattr__(self, "min_clearance", clearance)
        object.__setattr__(self, "collisions", bounded_int(self.collisions, "collisions", 0, 2**62))


def _tuple_of(value: object, name: str, cls: type) -> tuple[Any, ...]:
    if not isinstance(value, (tuple, list)):
        raise TypeError(f"{name} must be a tuple of {cls.__name__}, got {type(value).__name__}")
    for item in value:
        if not isinstance(item, cls):
            raise TypeError(f"{name} must hold {cls.__name__}s, got a {type(item).__name__}")
    return tuple(value)


def _readonly(arr: np.ndarray) -> np.ndarray:
    out = np.array(arr, dtype=np.float64, copy=True)
    out.flags.writeable = False
    return out


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class Trace:
    """Everything recorded during a :class:`Simulation` run, one row per physics step.

    Attributes
    ----------
    times : ndarray, shape (T,)
        Simulated times, s: row ``i`` at ``i / rate`` (row 0 is the start;
        0.3, not ``3 * 0.1`` = 0.30000000000000004, at 10 Hz).
    poses : ndarray, shape (T, 3)
        True poses ``[x, y, theta]``, m and rad.
    estimates : ndarray, shape (T, 3)
        The estimator's latest pose ``[x, y, theta]`` at each step, m and rad
        (NaN rows before the first estimate or without an estimator).
    commands : ndarray, shape (T, 3)
        The twist ``[vx, vy, omega]`` commanded at each step, m/s and rad/s
        (the controller's latest output, before the drive's limits).
    scans : tuple of ScanReading
        Every scan taken, when the run recorded them (``record_scans=True``).
    events : tuple of Event
        Collisions, reaching the goal and the end of the run, in order.
    metrics : Metrics
        The run's summary.

    Raises
    ------
    TypeError
        An array not of real numbers; ``scans``, ``events`` not tuples (or
        lists) of ScanReading, Event; ``metrics`` not a Metrics.
    ValueError
        ``times`` not one-dimensional or not finite; ``poses``, ``estimates``
        or ``commands`` not of shape (N, 3) for N times, ``poses`` or
        ``commands`` not finite, ``estimates`` holding an infinity.

    Notes
    -----
    Every array is a read-only copy (in copies and unpickled traces too).

    Examples
    --------
    >>> from navkit.geometry import Twist2D
    >>> from navkit.kinematics import DiffDrive
    >>> from navkit.sim import Observation, Robot, Simulation, World
    >>> robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2)
    >>> def forward(obs: Observation) -> Twist2D:  # 0.5 m/s straight ahead
    ...     return Twist2D(0.5, 0.0, 0.0)
    >>> trace = Simulation(World(), robot, forward, start=(0.0, 0.0, 0.0), duration=1.0).run()
    >>> len(trace), trace.poses.shape, trace.commands[-1].tolist()  # 100 Hz: 101 rows in 1 s
    (101, (101, 3), [0.5, 0.0, 0.0])
    >>> float(trace.times[-1]), trace.poses[-1].round(6).tolist()
    (1.0, [0.5, 0.0, 0.0])
    >>> bool(np.isnan(trace.estimates).all()), trace.poses.flags.writeable  # no estimator
    (True, False)
    >>> trace.metrics.reason, [event.kind for event in trace.events]
    ('timeout', ['timeout'])
    """

    times: FloatArray
    poses: FloatArray
    estimates: FloatArray
    commands: FloatArray
    scans: tuple[ScanReading, ...]
    events: tuple[Event, ...]
    metrics: Metrics

    __repr__ = bounded_repr  # a scan per recorded step: print a few

    def __post_init__(self) -> None:
        self._check(adopt=False)

    def _check(self, *, adopt: bool) -> None:
        """Check and store the fields; ``adopt``: own the given arrays, as they are."""
        times = as_float_array(self.times, "times", ndim=1)
        n = times.shape[0]
        if adopt and times is self.times:
            times.flags.writeable = False
        else:
            times = _readonly(times)
        object.__setattr__(self, "times", times)
        for name in ("poses", "estimates", "commands"):
            value = getattr(self, name)
            if issubclass(type(value), np.ndarray) and not adopt:
                value = value.copy()  # never touch the caller's array, even on failure
            finite = name != "estimates"
            arr = as_float_array(value, name, shape=(n, 3), finite=finite)
            if not finite and np.isinf(arr).any():
                raise ValueError(f"{name} must be finite or NaN, got an infinity")
            if arr is value and type(arr) is np.ndarray:
                # The copy above (or the adopted array), ours alone: stored as it is
                # (review 28: copied again, a whole run peaked at 2.85 times its trace;
                # a run's trace now adopts the run's arrays, see adopted_trace).
                arr.flags.writeable = False
            else:
                arr = _readonly(arr)
            object.__setattr__(self, name, arr)
        object.__setattr__(self, "scans", _tuple_of(self.scans, "scans", ScanReading))
        object.__setattr__(self, "events", _tuple_of(self.events, "events", Event))
        if not isinstance(self.metrics, Metrics):
            raise TypeError(f"metrics must be a Metrics, got {type(self.metrics).__name__}")

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, ("times", "poses", "estimates", "commands"))

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, the arrays read-only again."""
        restore_read_only(self, state, ("times", "poses", "estimates", "commands"))

    def __len__(self) -> int:
        return int(self.times.shape[0])


def adopted_trace(
    times: FloatArray,
    poses: FloatArray,
    estimates: FloatArray,
    commands: FloatArray,
    scans: tuple[ScanReading, ...],
    events: tuple[Event, ...],
    metrics: Metrics,
) -> Trace:
    """A :class:`Trace` that owns the given float64 arrays without copying them.

    For :class:`~navkit.sim.Simulation`, whose run hands over arrays nothing
    else refers to: they are checked as ``Trace(...)`` checks them and made
    read-only. A Trace of a whole run then takes no memory beyond the run's.

    Examples
    --------
    >>> nan = float("nan")
    >>> metrics = Metrics(False, "timeout", 0.01, nan, nan, nan, nan, nan, nan, 1.0, 0, 0.0)
    >>> times, poses = np.array([0.0, 0.01]), np.zeros((2, 3))
    >>> trace = adopted_trace(times, poses, np.full((2, 3), nan), np.zeros((2, 3)), (), (),
    ...                       metrics)
    >>> trace.poses is poses, poses.flags.writeable
    (True, False)
    """
    trace = object.__new__(Trace)
    for name, value in (
        ("times", times), ("poses", poses), ("estimates", estimates), ("commands", commands),
        ("scans", scans), ("events", events), ("metrics", metrics),
    ):  # fmt: skip
        object.__setattr__(trace, name, value)
    trace._check(adopt=True)
    return trace


def cross_track(points_xy: FloatArray, path_xy: FloatArray) -> FloatArray:
    """Distance from each point (N, 2) to the polyline ``path_xy`` (K, 2), shape (N,).

    Examples
    --------
    >>> cross_track(np.array([[1.0, 0.5]]), np.array([[0.0, 0.0], [2.0, 0.0]]))
    array([0.5])
    """
    out = np.empty(points_xy.shape[0])
    # Writeable C-contiguous copies where needed: a Path2D's points are read-only,
    # a list given as reference_path is not; one kernel specialisation serves both.
    points = kernel_input(np.asarray(points_xy, dtype=np.float64))
    path = kernel_input(np.asarray(path_xy, dtype=np.float64))
    segments = path.shape[0] - 1
    if segments > SIMPLE_MAX_SEGMENTS:
        # Long paths: the same distances, bit for bit, skipping far chunks of segments.
        point_polyline_distances_chunked(points, path, chunk_boxes(path), out)
    else:
        point_polyline_distances(points, path, out)
    return out


def nan_if_empty(values: FloatArray, fn: str) -> float:
    """``values.mean()`` or ``values.max()`` (``fn``), NaN for no values."""
    if values.size == 0:
        return math.nan
    return float(values.mean() if fn == "mean" else values.max())
