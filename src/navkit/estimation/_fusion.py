"""Planar fusion of wheel odometry with an IMU: the robot_localization-style 2-D EKF."""

from __future__ import annotations

import array
import enum
import math
import numbers
import sys
from _thread import get_ident
from bisect import bisect_right
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.counts import counted
from navkit._shared.frozen import (
    extra_state,
    frozen_setattr,
    reduce_record,
    restore_read_only,
    restore_slots,
)
from navkit._shared.locks import _in_use
from navkit._shared.times import as_time, as_times
from navkit._shared.types import BoolArray, FloatArray
from navkit._shared.validation import (
    as_array,
    as_float_array,
    bounded_int,
    finite_float,
    has_array_protocol,
    is_ndarray,
    unpack,
)
from navkit.errors import FilterError
from navkit.estimation import _fusion_kernels as k
from navkit.estimation._covariance import (
    MAX_COVARIANCE,
    MIN_VARIANCE,
    check_magnitude,
    covariance,
    negative_eigenvalue_note,
    not_given_hint,
    variance,
)
from navkit.estimation._fusion_kernels import (
    BUF_SAVED_TIME,
    BUF_TIME,
    BUF_UNDO,
    GATED,
    INVALID,
    NOT_POSITIVE_DEFINITE,
    OVERFLOW,
    TIME_GAP,
    planar_step_plain_entry,
    undo_step,
)
from navkit.estimation._gaussian import GaussianEstimate
from navkit.estimation._odometry import anchored
from navkit.estimation._result import UpdateResult, _Building, new_result, rejected_result
from navkit.geometry import Pose2D, as_pose, wrap_angle

__all__ = ["FusionResult", "FusionStatus", "MeasurementLog", "PlanarFusion"]

#: Default process noise per second for [x, y, θ, v, ω, a]: robot_localization's
#: default ``process_noise_covariance`` entries for the same variables.
DEFAULT_PROCESS_NOISE = (0.05, 0.05, 0.06, 0.025, 0.02, 0.01)
#: Default initial variances: pose known (it defines the frame), rates unknown.
DEFAULT_INITIAL_VARIANCE = (1e-9, 1e-9, 1e-9, 1.0, 1.0, 1.0)

# (first, count) of the consecutive components of [θ, v, ω, a] each online kind observes.
_KIND_COMPONENTS = {
    "odometry": (1, 2),
    "speed": (1, 1),
    "yaw": (0, 1),
    "yaw_rate": (2, 1),
    "acceleration": (3, 1),
}


# The array fields of the records, made read-only again in their copies and pickles.
_LOG_ARRAYS = ("times", "values", "variances", "observed")
_RESULT_ARRAYS = ("times", "states", "covariances", "status", "nis")

_R = TypeVar("_R")

# Argument names for error messages: (value 0, value 1, variance 0, variance 1).
_ODOMETRY_NAMES = ("v", "omega", "v_variance", "omega_variance")


#: Relative diagonal loading of a prediction whose update lost positive definiteness.
#: After a long time gap (weeks without measurements, at the default process noise) the
#: predicted covariance is positive definite only in exact arithmetic: heading and yaw
#: rate, speed and acceleration, position and heading are correlated to within rounding
#: (the correlation matrix's smallest eigenvalue at -1e-15 after 2e6 s), and the Joseph
#: update of any measurement then fails its check. Raising every variance by 2**-40 of
#: itself (9.1e-13, far below the model's own error over such a gap) restores it: each
#: of 378 such updates (gaps of 3e5 to 1e14 s, 5 kinds, 30 states) went through.
_LOADING = 2.0**-40
# Flat slices of the buffer: x and P, and their copy saved by the online step.
_STATE = slice(k.W * k.BUF_X, k.W * (k.BUF_P + 6))
_SAVED = slice(k.W * k._SAVED, k.W * (k._SAVED + 7))
_DIAGONAL = slice(k.W * k.BUF_P, k.W * (k.BUF_P + 6), k.W + 1)
# The residuals the step leaves in the last row of the measurement block.
_RESIDUALS = slice(k.W * (k.BUF_MEAS + 2), k.W * (k.BUF_MEAS + 3))


def _load(buf: FloatArray) -> None:
    """Raise the variances of the covariance in ``buf`` by :data:`_LOADING` of themselves."""
    buf[_DIAGONAL] += buf[_DIAGONAL] * _LOADING


def _load_step(*args: Any) -> tuple[int, float]:
    """Compile (or load) the online step on first use, then run it (see ``_step``)."""
    global _step
    _step = planar_step_plain_entry()
    return _step(*args)


# The online step (_fusion_kernels._planar_step) without numba's type dispatch, compiled
# on the first online update. Entered through planar_step_plain: a time, value or
# variance that is not a float (a NumPy float64 and an int float64 holds exactly count as
# floats) arrives as NaN, which the step refuses (INVALID, nothing changed), so the fast
# paths need no type checks in Python; every other caller passes validated floats.
_step: Callable[..., tuple[int, float]] = _load_step

# The arguments of an online step after its time: first, count, the values, the
# variances and the gate (see _fusion_kernels.planar_step).
_StepArgs = tuple[int, int, float, float, float, float, float]
# One step kept for `history`: its time, the filter time before it (NaN: the clock was
# not set), x and P before it (the flat block _STATE of the buffer), its arguments and
# its kind (for messages).
_Entry = tuple[float, float, FloatArray, _StepArgs, str]
# predict(t) kept as a step: no component observed.
_PREDICT: _StepArgs = (0, 0, 0.0, 0.0, 0.0, 0.0, math.inf)
# What takes the place of a step gone from the window until the list drops its slot
# (PlanarFusion._record): the step and its arrays are freed as it goes, not in bulk.
_GONE: _Entry = (math.nan, math.nan, np.empty(0), _PREDICT, "gone")


def _entry_time(entry: _Entry) -> float:
    return entry[0]


#: Relative slack of a late measurement's age. The age is a difference of two
#: rounded stamps: one exactly ``history`` old may come out above it (at 1.0 s a
#: stamp 0.7 is 0.3 s old, but 1.0 - 0.7 is 0.30000000000000004 > 0.3; 58 of 192
#: stamps t0 + k / rate exactly ``history`` late were refused). A stamp t0 + k / rate
#: is rounded twice, k / rate at |stamp - t0| <= |t0| + |stamp| and the sum at
#: |stamp|: the age is off by at most 2**-52 (|t0| + |now| + |stamp| + history),
#: where t0 is the clock's origin (_BUF_ORIGIN). Twice that is slack: 1.5 µs at epoch
#: stamps (1.7e9 s), far below any period. Without |t0| the slack missed the
#: rounding of stamps near 0 on clocks crossing it (t0 = -0.35 at 30 Hz: an age
#: 4.9e-17 over a slack of 4.4e-17 refused a measurement exactly ``history`` late).
_AGE_RTOL = 2.0**-51

#: Buffer index of the clock's origin, s: the time the clock was set at (t0 or the
#: first step's stamp; 0.0 before), the scale of the stamps' rounding in the age
#: slack. Entry 3 of the buffer's time row, which the kernels leave alone; a pickle
#: from before it holds 0.0 there (the slack it had then).
_BUF_ORIGIN = BUF_TIME + 3


#: The steps kept (PlanarFusion._record) go once older than ``history +
#: _TRIM_RTOL (|t0| + |t| + history)``: beyond _too_old's slack for every stamp,
#: however far back (|stamp| <= |t| + age), with a margin of 2**-50 (|t0| + |t| +
#: history) for the roundings. Trimmed at ``history`` itself, a step of a late
#: measurement's own stamp whose age rounded above it went, and the measurement, taken
#: by the slack, was fused after that step, where the tie order puts it before
#: (review 27).
_TRIM_RTOL = 4.0 * _AGE_RTOL


def _too_old(now: float, stamp: float, history: float, origin: float) -> bool:
    """Whether ``stamp`` is older than the filter time ``now`` by more than ``history``.

    Give or take the stamps' rounding (:data:`_AGE_RTOL`) on a clock set at ``origin``.
    """
    scale = abs(origin) + abs(now) + abs(stamp) + history
    return now - stamp > history + _AGE_RTOL * scale


# The order of steps with one stamp (history): MeasurementLog.from_streams's order at
# equal times, odometry (and speed) first, then yaw, yaw rate and acceleration; indexed
# by the first component a step observes. One kind keeps the order it came in (a
# stream's own order in from_streams, which sorts stably).
_TIE_RANKS = (1, 0, 2, 3)


def _tie_rank(args: _StepArgs) -> int:
    """The place of a step among the steps of its stamp (predict, observing nothing: -1)."""
    return _TIE_RANKS[args[0]] if args[1] else -1


class _IntCodes(enum.EnumMeta):
    """Enum metaclass whose lookup ``Enum(value)`` takes integer codes only.

    ``IntEnum`` finds its members by equality, so ``True`` and ``1+0j`` would
    pass for 1; they are refused (``TypeError``), like everywhere in navkit.
    A 0-d integer array (``np.array(1)``) is its integer, as for every navkit
    integer argument.
    """

    def __call__(cls, value: Any, *args: Any, **kwargs: Any) -> Any:
        if (
            not args
            and not kwargs
            and is_ndarray(value)
            and value.ndim == 0
            and value.dtype.kind in "iu"
        ):
            value = bounded_int(value, cls.__name__)  # masked entries refused
        if (
            not args
            and not kwargs
            and (isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral))
        ):
            raise TypeError(f"{cls.__name__} takes an integer code, got {type(value).__name__}")
        if not args and not kwargs and isinstance(value, np.integer):
            # Python's int: enum's message quoted np.int64(9) ("np.int64(9) is not a valid ...").
            value = int(value)
        return super().__call__(value, *args, **kwargs)


class FusionStatus(enum.IntEnum, metaclass=_IntCodes):
    """Outcome of one measurement: ``FusionResult.status`` and ``UpdateResult.status``.

    ``ACCEPTED``
        The row updated the state.
    ``GATED``
        Rejected by the Mahalanobis gate; the state keeps the prediction to the
        row's time.
    ``NOT_POSITIVE_DEFINITE``
        The update would lose positive definiteness; the state keeps the
        prediction.
    ``OUT_OF_ORDER``
        Older than the filter time (online, with ``PlanarFusion(history=)``:
        older than its window); skipped, state and time unchanged.
    ``TIME_GAP``
        Predicting over the time since the previous row would overflow float64
        (a corrupt timestamp such as 1e300 s); skipped, state and time unchanged,
        so later rows continue from the last good state.
    ``OVERFLOW``
        The update would overflow float64 (a value absurdly far from the state
        for its variance); the state keeps the prediction.

    The codes of each row of :meth:`PlanarFusion.update_batch`, and the
    ``status`` of the :class:`UpdateResult` of an online update
    (``PlanarFusion.update_*``, :meth:`ExtendedKalmanFilter.update`):
    ``ACCEPTED``, ``GATED``, ``OVERFLOW`` or (PlanarFusion) ``OUT_OF_ORDER``
    there, the filter otherwise as described (an EKF has no prediction in
    its update: its state is unchanged); online, a loss of positive
    definiteness or a time gap raises :class:`~navkit.errors.FilterError`
    instead.

    Examples
    --------
    >>> FusionStatus(1).name, int(FusionStatus.OUT_OF_ORDER)
    ('GATED', 3)
    """

    ACCEPTED = k.ACCEPTED
    GATED = k.GATED
    NOT_POSITIVE_DEFINITE = k.NOT_POSITIVE_DEFINITE
    OUT_OF_ORDER = k.OUT_OF_ORDER
    TIME_GAP = k.TIME_GAP
    OVERFLOW = k.OVERFLOW


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class MeasurementLog:
    """Timestamped measurements for :meth:`PlanarFusion.update_batch`.

    Each row is one measurement at ``times[i]`` of a subset of the observation
    vector ``[θ, v, ω, a]`` (absolute yaw, forward speed, yaw rate, forward
    acceleration) with independent noise. Rows are applied in the given order;
    a row older than the filter's time is rejected (``OUT_OF_ORDER``), exactly as
    in the online API without ``PlanarFusion(history=)``. :meth:`from_streams`
    builds a time-sorted log from separate sensor streams.

    Parameters
    ----------
    times : array_like, shape (T,)
        Measurement times, s (any finite values; integers beyond 2**53 and
        float16 / float32 times coarser than 1 ms are refused, see the notes
        on time stamps of :class:`PlanarFusion`).
    values : array_like, shape (T, 4)
        ``[yaw (rad), v (m/s), omega (rad/s), a (m/s²)]``, finite where
        observed; entries not observed are ignored (they may be NaN).
    variances : array_like, shape (T, 4)
        Noise variances of the observed entries, in [1e-100, 1e100] (SI units
        squared); others are ignored.
    observed : array_like of bool, shape (T, 4)
        Which components each row measures (at least one per row).

    Examples
    --------
    >>> log = MeasurementLog.from_streams(
    ...     odometry=([0.0, 0.1], [1.0, 1.0], [0.0, 0.0]), yaw=([0.05], [0.0]))
    >>> log.times, log.observed.astype(int).tolist()
    (array([0.  , 0.05, 0.1 ]), [[0, 1, 1, 0], [1, 0, 0, 0], [0, 1, 1, 0]])
    """

    times: FloatArray
    values: FloatArray
    variances: FloatArray
    observed: BoolArray

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self, times: ArrayLike, values: ArrayLike, variances: ArrayLike, observed: ArrayLike
        ) -> None: ...

    def __post_init__(self) -> None:
        times = as_times(self.times, "times")
        n = times.shape[0]
        # as_array, not np.asarray: a masked array's masked entries would be read as
        # their data, and a ragged nesting raise NumPy's message, naming nothing.
        obs = as_array(self.observed, "observed")
        if obs.dtype != np.bool_:
            raise TypeError(f"observed must be a boolean array, got dtype {obs.dtype}")
        if obs.shape != (n, 4):
            raise ValueError(f"observed must have shape ({n}, 4), got {obs.shape}")
        if n and not np.all(obs.any(axis=1)):
            raise ValueError("every row of observed must mark at least one component")
        values = as_float_array(self.values, "values", shape=(n, 4), finite=False)
        var = as_float_array(self.variances, "variances", shape=(n, 4), finite=False)
        if not np.all(np.isfinite(values[obs])):
            raise ValueError("values must be finite where observed")
        seen = var[obs]
        if not np.all((seen >= MIN_VARIANCE) & (seen <= MAX_COVARIANCE)):
            raise ValueError(
                f"variances must be in [{MIN_VARIANCE:g}, {MAX_COVARIANCE:g}] where observed"
                + not_given_hint(seen)
            )
        # Unobserved entries are never read by the kernel; zero them so the arrays are clean.
        values = np.where(obs, values, 0.0)
        var = np.where(obs, var, 1.0)
        # C order whatever the caller's layout (a transposed (4, T) array is Fortran
        # ordered): planar_run is compiled for C-ordered arrays only, and a Fortran
        # ordered log would make numba compile it a second time (issue 17).
        # values and var are np.where's own arrays (C order unless the caller's were
        # Fortran ordered): frozen as they are, not copied a second time.
        del seen
        times = np.array(times, dtype=np.float64, copy=True, order="C")
        for name, arr in (("times", times), ("values", values), ("variances", var)):
            arr = np.ascontiguousarray(arr)
            arr.flags.writeable = False
            object.__setattr__(self, name, arr)
        obs = np.array(obs, copy=True, order="C")
        obs.flags.writeable = False
        object.__setattr__(self, "observed", obs)

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, _LOG_ARRAYS)

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, the arrays read-only again."""
        restore_read_only(self, state, _LOG_ARRAYS)

    def __len__(self) -> int:
        return int(self.times.shape[0])

    @classmethod
    def from_streams(
        cls,
        *,
        odometry: tuple[ArrayLike, ...] | None = None,
        odometry_variance: tuple[ArrayLike, ArrayLike] = (1e-3, 1e-3),
        yaw: tuple[ArrayLike, ArrayLike] | None = None,
        yaw_variance: ArrayLike = 1e-3,
        yaw_rate: tuple[ArrayLike, ArrayLike] | None = None,
        yaw_rate_variance: ArrayLike = 1e-4,
        acceleration: tuple[ArrayLike, ArrayLike] | None = None,
        acceleration_variance: ArrayLike = 1e-2,
    ) -> MeasurementLog:
        """Merge sensor streams into one time-sorted log.

        Parameters
        ----------
        odometry : (t, v, omega) or (t, v), optional
            Wheel odometry: times (s), forward speeds (m/s) and, unless omitted
            (e.g. a skid-steer robot whose wheel yaw rate is unreliable), yaw
            rates (rad/s); each shape (T_o,).
        odometry_variance : (v_variance, omega_variance)
            Variances, scalars or shape (T_o,) arrays ((m/s)², (rad/s)²); every
            variance in [1e-100, 1e100]. ``omega_variance`` is not read (nor
            checked) when ``odometry`` has no yaw rates.
        yaw : (t, yaw), optional
            Times (s) and absolute yaws (rad), e.g. from a compass or the IMU
            orientation; each shape (T_y,).
        yaw_variance : float or array_like, shape (T_y,)
            rad².
        yaw_rate : (t, omega), optional
            Times (s) and gyro yaw rates (rad/s); each shape (T_g,).
        yaw_rate_variance : float or array_like, shape (T_g,)
            (rad/s)².
        acceleration : (t, a), optional
            Times (s) and forward accelerations (m/s², gravity removed); each
            shape (T_a,).
        acceleration_variance : float or array_like, shape (T_a,)
            (m/s²)².

        Returns
        -------
        MeasurementLog
            Rows sorted by time (stable: at equal times odometry comes first,
            then yaw, yaw rate and acceleration); ``T_o + T_y + T_g + T_a``
            rows of the streams given.

        Raises
        ------
        TypeError, ValueError
            No stream, a stream that is not a tuple of arrays of one length,
            values or variances outside their ranges, or times refused as in
            :class:`MeasurementLog`, naming the argument.

        Examples
        --------
        >>> log = MeasurementLog.from_streams(
        ...     odometry=([0.0, 0.2], [1.0, 1.0]), odometry_variance=(0.01, 1.0),
        ...     yaw=([0.1], [0.5]), yaw_variance=1e-3)
        >>> log.times
        array([0. , 0.1, 0.2])
        >>> log.observed.astype(int).tolist()  # columns [θ, v, ω, a]; no yaw rates given
        [[0, 1, 0, 0], [1, 0, 0, 0], [0, 1, 0, 0]]
        >>> log.values[:, :2].tolist(), float(log.variances[1, 0])
        ([[0.0, 1.0], [0.5, 0.0], [0.0, 1.0]], 0.001)
        """
        blocks: list[tuple[FloatArray, FloatArray, FloatArray, BoolArray]] = []
        if odometry is not None:
            parts = _stream(odometry, "odometry", (2, 3))
            odo_var = _pair(odometry_variance, "odometry_variance", rates=len(parts) == 3)
            t = parts[0]
            comps = {}
            for comp, val in enumerate(parts[1:], start=1):
                name = f"odometry_variance[{comp - 1}]"
                comps[comp] = (val, _stream_variance(odo_var[comp - 1], name, t.shape[0]))
            blocks.append(_block(t, comps))
        singles = (
            (yaw, yaw_variance, "yaw", 0),
            (yaw_rate, yaw_rate_variance, "yaw_rate", 2),
            (acceleration, acceleration_variance, "acceleration", 3),
        )
        for stream, stream_variance, name, comp in singles:
            if stream is not None:
                t, val = _stream(stream, name, (2,))
                var = _stream_variance(stream_variance, f"{name}_variance", t.shape[0])
                blocks.append(_block(t, {comp: (val, var)}))
        if not blocks:
            raise ValueError("give at least one measurement stream")
        times = np.concatenate([b[0] for b in blocks])
        order = np.argsort(times, kind="stable")
        # One column at a time, each block's part freed once merged: the blocks
        # and the merged columns were alive together (memory, review 28).
        columns: list[list[FloatArray]] = [list(c) for c in zip(*blocks, strict=True)]
        del blocks
        merged: list[FloatArray] = []
        for column in columns:
            merged.append(np.concatenate(column)[order])
            column.clear()
        del times, order
        return cls(*merged)


def _stream(stream: Any, name: str, widths: tuple[int, ...]) -> tuple[FloatArray, ...]:
    want = " or ".join(str(w) for w in widths)
    try:
        parts = unpack(stream, name)
    except TypeError:
        raise TypeError(f"{name} must be a tuple of {want} arrays") from None
    if len(parts) not in widths:
        raise ValueError(f"{name} must be a tuple of {want} arrays, got {len(parts)}")
    t = as_times(parts[0], f"{name}[0] (times)")
    rest = tuple(
        as_float_array(p, f"{name}[{i + 1}]", shape=(t.shape[0],)) for i, p in enumerate(parts[1:])
    )
    return (t, *rest)


def _pair(value: Any, name: str, *, rates: bool) -> tuple[Any, Any]:
    """``(v_variance, omega_variance)``; ``rates``: whether the odometry has yaw rates."""
    # A 0-d array is an ndarray without a length (len() would raise unnamed).
    if isinstance(value, (memoryview, array.array)) or (
        not (isinstance(value, (str, bytes, tuple, list)) or is_ndarray(value))
        and has_array_protocol(value)
    ):
        # A pair of numbers in a buffer (array.array("d"), a memoryview, possibly
        # big-endian) or a foreign array type: read as NumPy reads it.
        try:
            value = unpack(value, name)
        except TypeError:  # a 0-d array, a format NumPy cannot read
            raise TypeError(f"{name} must be a pair (v_variance, omega_variance)") from None
    if (
        isinstance(value, (str, bytes))
        or not (isinstance(value, (tuple, list)) or is_ndarray(value))
        or (is_ndarray(value) and value.ndim == 0)
    ):
        raise TypeError(f"{name} must be a pair (v_variance, omega_variance)")
    if len(value) != 2:
        # Most often one variance per sample given bare: say how to give those.
        hint = (
            "a pair of arrays, (v_variances, omega_variances)"
            if rates
            else "(v_variances, 1.0): the second is not read, the odometry having no yaw rates"
        )
        got = counted(len(value), "item")
        raise ValueError(
            f"{name} must be a pair (v_variance, omega_variance), got {got}; "
            f"for one variance per sample give {hint}"
        )
    return value[0], value[1]


def _stream_variance(value: ArrayLike, name: str, n: int) -> FloatArray:
    var = as_float_array(value, name)
    if var.ndim == 0:
        var = np.full(n, float(var))
    elif var.shape != (n,):
        raise ValueError(f"{name} must be a scalar or have shape ({n},), got {var.shape}")
    if not np.all((var >= MIN_VARIANCE) & (var <= MAX_COVARIANCE)):
        raise ValueError(
            f"{name} must be in [{MIN_VARIANCE:g}, {MAX_COVARIANCE:g}]" + not_given_hint(var)
        )
    return var


def _block(
    t: FloatArray, comps: dict[int, tuple[FloatArray, FloatArray]]
) -> tuple[FloatArray, FloatArray, FloatArray, BoolArray]:
    n = t.shape[0]
    values = np.zeros((n, 4))
    var = np.ones((n, 4))
    obs = np.zeros((n, 4), dtype=np.bool_)
    for comp, (val, v) in comps.items():
        values[:, comp] = val
        var[:, comp] = v
        obs[:, comp] = True
    return t, values, var, obs


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class FusionResult:
    """Filter output over a :class:`MeasurementLog`, one row per measurement.

    Row ``k`` is the filter after row ``k`` of the log: T rows for T
    measurements. The state before the log (``x0``, or the filter's ``x``
    when :meth:`PlanarFusion.update_batch` was called) is not a row, as in
    :meth:`DiffOdometry.update_batch`; :func:`navkit.geometry.rollout` and
    :meth:`OmniOdometry.update_batch`, which take increments, return the start
    as row 0 and T + 1 rows.

    Attributes
    ----------
    times : ndarray, shape (T,)
        Measurement times, s (the log's).
    states : ndarray, shape (T, 6)
        ``[x, y, θ, v, ω, a]`` after each row (m, m, rad, m/s, rad/s, m/s²).
    covariances : ndarray, shape (T, 6, 6)
        State covariance after each row.
    status : ndarray of int8, shape (T,)
        :class:`FusionStatus` code of each row.
    nis : ndarray, shape (T,)
        Normalised innovation squared of each row, >= 0: NaN when it was never
        computed (``OUT_OF_ORDER``, ``TIME_GAP``), inf when it overflowed
        (``OVERFLOW``).

    Notes
    -----
    Every array is a read-only copy (the caller's arrays are never made
    read-only or modified). ``times``, ``states`` and ``covariances`` must be
    finite.

    Examples
    --------
    >>> result = PlanarFusion(t0=0.0).update_batch(
    ...     MeasurementLog.from_streams(odometry=([0.1, 0.2], [1.0, 1.0], [0.0, 0.0])))
    >>> result.states.shape, result.accepted.tolist()
    ((2, 6), [True, True])
    """

    times: FloatArray
    states: FloatArray
    covariances: FloatArray
    status: NDArray[np.int8]
    nis: FloatArray

    def __post_init__(self) -> None:
        times = as_times(self.times, "times")
        n = times.shape[0]
        states = as_float_array(self.states, "states", shape=(n, 6))
        cov = as_float_array(self.covariances, "covariances", shape=(n, 6, 6))
        nis = as_float_array(self.nis, "nis", shape=(n,), finite=False)
        if np.any(nis < 0.0):
            raise ValueError("nis must be >= 0 (inf when it overflowed) or NaN (not computed)")
        raw_status = as_array(self.status, "status")  # masked or ragged: refused, named
        if raw_status.dtype.kind not in "iu":
            raise TypeError(f"status must hold integer codes, got dtype {raw_status.dtype}")
        if raw_status.shape != (n,):
            raise ValueError(f"status must have shape ({n},), got {raw_status.shape}")
        if not np.all(np.isin(raw_status, [int(code) for code in FusionStatus])):
            raise ValueError("status must hold FusionStatus codes")
        status = raw_status.astype(np.int8)
        fields = (
            ("times", times),
            ("states", states),
            ("covariances", cov),
            ("status", status),
            ("nis", nis),
        )
        for name, arr in fields:
            owned = np.array(arr, copy=True)
            owned.flags.writeable = False
            object.__setattr__(self, name, owned)

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, _RESULT_ARRAYS)

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, the arrays read-only again."""
        restore_read_only(self, state, _RESULT_ARRAYS)

    @property
    def accepted(self) -> BoolArray:
        """Boolean mask (T,) of rows that updated the state."""
        return np.asarray(self.status == FusionStatus.ACCEPTED)

    @property
    def final_pose(self) -> Pose2D:
        """Pose after the last row."""
        if self.states.shape[0] == 0:
            raise ValueError("the result is empty")
        return Pose2D(*(float(v) for v in self.states[-1, :3]))


_FUSION_RESULT_SETTERS = tuple(
    FusionResult.__dict__[name].__set__
    for name in ("times", "states", "covariances", "status", "nis")
)


def _fusion_result(
    times: FloatArray,
    states: FloatArray,
    covariances: FloatArray,
    status: NDArray[np.int8],
    nis: FloatArray,
) -> FusionResult:
    """Build a :class:`FusionResult` from arrays the caller owns, without copying them.

    The validating constructor copies every array; the covariances alone are
    288 bytes a row (29 MB for 100,000 rows), and copying them would add a few
    milliseconds (5-10 %) to :meth:`PlanarFusion.update_batch`. The filter's
    output arrays are fresh and referenced by nothing else, so they are only
    made read-only; ``times`` is the log's, already a read-only copy.
    """
    result: FusionResult = object.__new__(FusionResult)
    arrays: tuple[NDArray[Any], ...] = (times, states, covariances, status, nis)
    for setter, arr in zip(_FUSION_RESULT_SETTERS, arrays, strict=True):
        arr.flags.writeable = False
        setter(result, arr)
    return result


#: The slots of PlanarFusion and its base before the filter reduced itself (1efa428),
#: from 0123de4 on: what an old pickle holds beside a subclass's own attributes.
_OLD_SLOTS = frozenset(
    ("_buf", "_gates", "_kinds", "_odometry_gate", "_odometry_residual", "_p", "_q",
     "_residuals", "_t", "_work", "_x")
)  # fmt: skip


class PlanarFusion(GaussianEstimate):
    r"""2-D EKF fusing wheel odometry with an IMU (robot_localization in two_d_mode).

    State ``[x, y, θ, v, ω, a]``: world position (m), heading (rad, (-π, π]),
    forward speed (m/s), yaw rate (rad/s), forward acceleration (m/s²). Motion
    model: constant-acceleration unicycle — over ``dt`` the robot travels
    :math:`s = v\,dt + a\,dt^2/2` along the mid-step heading
    :math:`\theta + \omega\,dt/2` (second order in ``dt``), then
    :math:`\theta \mathrel{+}= \omega\,dt`, :math:`v \mathrel{+}= a\,dt`; the
    process noise is given per second and scaled by ``dt`` (as robot_localization
    does). Measurements are linear in the state: absolute yaw θ (compass or IMU
    orientation; residual wrapped), wheel odometry (v, ω), gyro yaw rate ω and
    forward acceleration a — the observation vector [θ, ẋ, θ̇, ẍ]. Updates use the
    Joseph form and keep ``P`` symmetric positive definite.

    Measurements arrive asynchronously: each update first predicts the state to
    the measurement's time. A measurement older than the filter's time is not
    applied and the filter is untouched; its :class:`UpdateResult` says so
    (``accepted=False`` with a reason, ``OUT_OF_ORDER``), unless ``history``
    reaches back to it (see the notes on late measurements). A measurement
    rejected by the gate still advances the filter to its time (the
    prediction is kept, the update skipped).
    The first measurement (when ``t0`` is not given) sets the clock without a
    prediction. A numerical failure raises :class:`~navkit.errors.FilterError`
    and leaves the filter untouched — among them a time gap so large that the
    prediction would overflow float64 (e.g. a corrupt timestamp of 1e300 s). A
    measurement whose update would overflow (a value absurdly far from the state
    for its variance, such as a speed of 1e308 m/s) is not applied:
    ``accepted=False`` with the reason, the prediction is kept. The state never
    becomes NaN or infinite. After a long time without measurements (weeks at
    the default process noise: a robot paused, then resumed) the predicted
    covariance is positive definite only in exact arithmetic, its rounding
    having made it indefinite, and an update would fail its check: such an
    update is redone from the prediction with every variance raised by 2⁻⁴⁰
    of itself (online and in :meth:`update_batch` alike), and the filter goes
    on; it raises only if that fails too.
    Predict and update run in one compiled kernel per call; :meth:`update_batch`
    fuses a whole log in one kernel call. Several readings with one timestamp
    (e.g. the yaw, yaw rate and acceleration of one IMU message) can be given by
    successive calls: with independent noise and linear measurements this equals
    one joint update (to rounding), as long as the yaw residual stays well within
    ±π. A yaw reading nearly opposite to the estimate is ambiguous: an update
    before it (a yaw rate, say) can move the estimate across ±π, and the order
    of the calls then decides which way the yaw pulls it (with ``history``, the
    order at one stamp given in the notes on late measurements decides,
    whatever the calls' order). In every ``update_*``
    method the time and the measured value(s) are positional and every variance
    is keyword-only.

    An ordinary class with ``__slots__`` rather than a frozen dataclass: every
    measurement changes its estimate in place.

    Parameters
    ----------
    x0 : array_like, shape (6,), optional
        Initial state ``[x, y, yaw, v, omega, a]`` (finite); default zeros.
    P0 : array_like, shape (6, 6) or (6,), optional
        Initial covariance (or its diagonal), positive definite, entries of
        magnitude at most 1e100; default ``diag(1e-9, 1e-9, 1e-9, 1, 1, 1)``:
        pose known, rates unknown.
    process_noise : array_like, shape (6, 6) or (6,), optional
        Process noise covariance per second (or its diagonal), positive
        semi-definite, entries of magnitude at most 1e100; default
        robot_localization's defaults ``(0.05, 0.05, 0.06, 0.025, 0.02, 0.01)``.
    t0 : float, optional
        Time of ``x0``, s (any finite value; so are measurement times; see
        the notes on time stamps).
    pose : Pose2D or array_like (x, y, theta), optional
        The start pose alone, keyword-only, as the odometry classes and the
        simulator take it: ``x0`` with zero rates. Not with ``x0``.
    gate_probability : float, optional
        If given, in (0, 1): reject measurements whose NIS exceeds the chi-square
        quantile of this probability for their dimension (Mahalanobis gate). A
        probability, not a threshold: ``ExtendedKalmanFilter.update(gate=)``
        takes the quantile itself, ``scipy.stats.chi2.ppf(gate_probability, m)``
        for a measurement of dimension ``m``. robot_localization's
        ``*_rejection_threshold`` is a Mahalanobis distance, the square root
        of an NIS threshold, one for every dimension. The gate trusts the
        process noise and the variances: readings that change faster than
        the process noise allows, or a sensor whose variances are too small,
        are rejected as outliers would be, and a rate left uncorrected puts
        the next reading further off, so the rejections can go on for
        seconds. On robot_localization's test2 bag, fused as its own test
        fuses it but gated at 0.997, 6,581 of 12,243 readings were rejected
        and the end moved 34 m (0.013 m from that test's accepted end
        without the gate; review 46). robot_localization gates nothing by
        default.
    history : float, optional
        Keyword-only, s, finite and >= 0 (default 0): how far back before the
        filter time a late measurement is still fused online, as
        robot_localization's ``smooth_lagged_data`` with ``history_length``
        (see the notes on late measurements). 0: measurements are taken in
        stamp order only.

    Notes
    -----
    Measured values are any finite numbers; measurement variances (keyword-only
    in every ``update_*`` method) are in [1e-100, 1e100], SI units squared.

    Time stamps are float64 seconds (a ROS stamp: ``sec + nanosec * 1e-9``).
    Each prediction's ``dt`` is the difference of two stamps (exact in float64
    for stamps within a factor 2 of each other) and the filter time is the
    last stamp, never a sum: at epoch stamps (1.78e9 s, where float64 values
    lie 2**-22 s = 2.4e-7 s apart) a stamp is rounded by up to 1.2e-7 s and
    the ``dt`` of a 1 kHz stream by up to 2.4e-7 s (0.024 %), but nothing
    accumulates: a run shifted by one of its own stamps gives the same numbers
    bit for bit, and 10^5 steps at 1 kHz end within 1e-6 m of the same run
    from 0 s. Stamps that round to one float (1 ns apart) are one time (no
    prediction between them); a float one spacing earlier is out of order.
    Integers beyond 2**53 (integer nanoseconds, 1.78e18) and float16 / float32
    times coarser than 1 ms (float32 from 2**14 s, 4.6 h, on; an epoch stamp in
    float32 is 128 s coarse) are refused with a ``ValueError``: float64 would
    round the one, and the other has lost its timing already.

    The filter time only moves forward, and nothing is raised when the
    stamps jump: after a clock that went back (a bag played again with
    ``--loop``, a system clock stepped back, a sensor restarted on another
    clock) every measurement older than the newest one taken is refused
    (``OUT_OF_ORDER``, unless within ``history``) until the stamps pass it;
    one stamp far ahead (a corrupt stamp, a clock stepped forward) moves the
    filter time there, predicting over the whole gap, with the same effect
    on the measurements after it (a yaw stamped 1000 s ahead of a robot
    driving at 0.5 m/s: the estimate moved 500 m and the next 1000 odometry
    messages, 20 s of them, were all refused). A node that runs for days
    should watch ``UpdateResult.status`` and restart the clock with
    ``fusion.reset(fusion.x, fusion.P)`` (the estimate kept, the next
    measurement sets the time), as robot_localization does on a jump back in
    time (``reset_on_time_jump``).

    Position is never measured: x and y are dead reckoning. The filter keeps
    the start position (``x0``, within ±1e15 m) apart and sums the motion from
    it, so that a start far from the origin (UTM coordinates, 5e6 m, where
    float64 values lie 9.3e-10 m apart) gives the run from the origin shifted,
    to within a few float spacings: each step added to the coordinates
    themselves would be rounded at their size, with one sign for steady motion
    (1 kHz odometry from a northing of 5e6 m drifted by 1.6 cm per 100 km).
    :attr:`x`, :attr:`pose` and :meth:`update_batch`'s states are the world
    values; from a start at the origin they are the sums themselves, bit for bit.

    Late measurements (``history`` > 0): the filter keeps each online step
    (update or :meth:`predict`) of the last ``history`` seconds with the state
    before it. A measurement older than the filter time ``t`` by at most
    ``history`` (``t - stamp <= history``, give or take ``2**-51 (|t0| + |t| +
    |stamp| + history)`` for the stamps' rounding, ``t0`` the time the clock was
    set at, 1.5 µs at epoch stamps: at 1.0 s a stamp 0.7 is 0.3 s old, though
    ``1.0 - 0.7`` rounds to 0.30000000000000004)
    goes back to the state before the
    first step later than it, is fused there, and the later steps are taken
    again: whatever order they came in, the filter ends as if the measurements
    had come in stamp order, the same numbers, bit for bit, as
    :meth:`update_batch` of the log :meth:`MeasurementLog.from_streams` makes
    of them, and its time stays the newest stamp. At one stamp that log's
    order holds too: odometry (or speed), yaw, yaw rate, acceleration, and
    one kind in the order it came (its stream's order), so a measurement
    stamped as the newest steps but before them in that order goes back
    the same way. Its :class:`UpdateResult` is its own update's, as of its
    stamp; the later steps' gate decisions may change. An older measurement
    is refused (``OUT_OF_ORDER``), as is one older than ``t0`` or than the
    last row of an :meth:`update_batch` (its rows are not kept: sort a log
    instead; one stamped as that row goes after it).
    A late measurement costs one step per later step kept (about
    1 µs each); the steps kept take about 0.7 kB each (0.17 MB a second for
    50 Hz odometry and a 200 Hz IMU's yaw rate), and keeping them about 0.8 µs
    a measurement. A ``KeyboardInterrupt`` during an update drops them
    (later late measurements are refused until the window has filled again),
    and so does :meth:`reset`. Copies and pickles keep them, except one made
    during a call of the filter (by a signal handler or another thread), which
    may be between a step and its record and so keeps none; copying is then a
    call of the filter itself (another thread's call meanwhile raises
    ``RuntimeError``, see below).
    The window is one of time, not of steps: every step of one stamp is kept,
    and a measurement that goes before them in the order at that stamp takes
    them all again. Stamps that do not advance (a driver that leaves them 0,
    one stamp repeated) thus grow the steps kept without bound, each such
    measurement costing more than the last: 10,000 yaw and odometry pairs at
    one stamp kept 20,000 steps and took 2 minutes in all (5,000 pairs: 33 s).
    Give such streams real stamps, or use ``history=0``.

    A filter keeps its estimate between calls, so it is not thread-safe: one
    thread at a time may call its methods (in a ROS 2 node with a
    ``MultiThreadedExecutor``, put the callbacks that use it in one
    ``MutuallyExclusiveCallbackGroup``); different filters may run in
    different threads at once. With ``history``, an update, :meth:`predict`,
    :meth:`reset` or :meth:`update_batch` called while another is under way
    (another thread's, or a signal handler's interrupting one in the same
    thread) raises ``RuntimeError`` and changes nothing; the call under way
    goes on as alone (before, such a pair kept the steps out of time order or
    lost one of the two measurements, and later late measurements were fused
    wrongly, without an error). The check costs about 0.2 µs a call, an
    eighth of a step kept for ``history`` (about 1.8 µs). Without ``history``
    the calls are not checked (the check would be a fifth of a step of about
    1 µs): two at once may leave a wrong estimate or result without an error.
    A copy or pickle taken during a call (another thread's, a signal
    handler's) is the filter as before or after one of that call's steps,
    with or without ``history``.

    Subclasses may add attributes (their own ``__slots__`` or an instance
    ``__dict__``) and methods, and override the public methods, calling the
    base's through ``super()``: no public method calls another (a late
    measurement replays the steps after it, and :meth:`update_batch` steps,
    without :meth:`predict` or the updates), so an override of one changes
    only its own callers. The same holds for the properties (:attr:`t`,
    :attr:`x`, :attr:`P`, :attr:`pose`, :attr:`history`): the filter's own
    methods, ``repr`` among them, read its state directly, never through a
    property, so an override changes what its callers read and not the
    filter's arithmetic. Copies
    (:func:`copy.copy`, :func:`copy.deepcopy`) and pickles rebuild a subclass
    as itself, with what it adds and the steps kept for late measurements
    (its ``__init__`` is not called), and ``repr`` names it. Names with a
    leading underscore (the compiled kernels, the filter's buffer and its
    views, the steps kept) are private: a subclass must neither use nor
    override them; they may change in any release.

    Raises
    ------
    TypeError, ValueError
        An argument outside the ranges above, naming it.

    Examples
    --------
    >>> fusion = PlanarFusion()
    >>> for i in range(101):
    ...     res = fusion.update_odometry(0.01 * i, 1.0, 0.0, v_variance=1e-4, omega_variance=1e-4)
    >>> round(fusion.pose.x, 3), round(float(fusion.x[3]), 3)
    (1.0, 1.0)
    >>> fusion.update_yaw(0.5, 0.0, variance=1e-3).reason
    'out of order: t=0.5 s is older than the filter time 1.0 s'
    >>> PlanarFusion(pose=(2.0, 1.0, 0.5), t0=0.0).x.tolist()
    [2.0, 1.0, 0.5, 0.0, 0.0, 0.0]

    With ``history``, a late measurement is fused where it belongs in time:

    >>> late = PlanarFusion(t0=0.0, history=0.5)
    >>> for t in (0.1, 0.2, 0.3):
    ...     _ = late.update_odometry(t, 1.0, 0.0, v_variance=1e-4, omega_variance=1e-4)
    >>> late.update_yaw_rate(0.15, 0.0, variance=1e-4).accepted, late.t
    (True, 0.3)
    >>> in_order = PlanarFusion(t0=0.0).update_batch(MeasurementLog.from_streams(
    ...     odometry=([0.1, 0.2, 0.3], [1.0] * 3, [0.0] * 3), odometry_variance=(1e-4, 1e-4),
    ...     yaw_rate=([0.15], [0.0]), yaw_rate_variance=1e-4))
    >>> bool((late.x == in_order.states[-1]).all())
    True
    """

    __slots__ = (
        "_age_scale",
        "_anchor",
        "_buf",
        "_callers",
        "_gates",
        "_head",
        "_history",
        "_kinds",
        "_odometry_gate",
        "_odometry_residual",
        "_q",
        "_residuals",
        "_saved",
        "_steps",
    )

    def __init__(
        self,
        x0: ArrayLike | None = None,
        P0: ArrayLike | None = None,
        *,
        process_noise: ArrayLike | None = None,
        t0: float | None = None,
        gate_probability: float | None = None,
        pose: Pose2D | ArrayLike | None = None,
        history: float = 0.0,
    ) -> None:
        x = _start_state(x0, pose)
        gates = np.full(5, np.inf)
        if gate_probability is not None:
            prob = finite_float(gate_probability, "gate_probability")
            if not 0.0 < prob < 1.0:
                raise ValueError(f"gate_probability must be in (0, 1), got {prob}")
            # The chi-square quantile as scipy.stats.chi2.ppf computes it, without
            # importing scipy.stats (0.7 s on first use; scipy.special is 0.2 s).
            from scipy.special import gammaincinv

            gates[1:] = 2.0 * gammaincinv(np.arange(1, 5) / 2.0, prob)
        window = finite_float(history, "history")
        if window < 0.0:
            raise ValueError(f"history must be >= 0 s, got {window}")
        buf, anchor = _start_buffer(x, P0, t0, process_noise=process_noise)
        self._adopt(buf, gates, anchor, window)

    def _adopt(
        self,
        buf: FloatArray,
        gates: FloatArray,
        anchor: tuple[float, float] = (0.0, 0.0),
        history: float = 0.0,
        entries: list[_Entry] | None = None,
    ) -> None:
        """Take ``buf`` (see _fusion_kernels.BUF_*) and the chi-square ``gates`` as the filter's.

        ``anchor`` is the world position that the buffer's x and y are relative to;
        ``history`` the window (s) and ``entries`` the steps kept for it.
        """
        self._anchor = anchor
        self._history = history
        # The calls under way, with history (one at most: see _one_at_a_time; not
        # copied or pickled).
        self._callers: list[tuple[int, str, object]] = []
        # |origin| + history: the part of the age slack's scale fixed while the clock
        # runs, read by every step kept (_record), which the buffer's item would slow.
        self._age_scale = abs(buf.item(_BUF_ORIGIN)) + history
        # The steps kept are _steps[_head:], in time order; the slots before _head are
        # _GONE, dropped together once they are half the list (see _record). The list
        # is empty when no step is kept (so _steps[-1] is the newest kept, if any).
        self._steps: list[_Entry] = [] if entries is None else entries
        self._head = 0
        self._buf = buf
        self._gates = gates
        # x, P, Q and the residuals are views of the buffer's rows: the kernels update
        # the buffer in place, and the properties read it through these.
        rows = buf.reshape(k.BUF_ROWS, k.W)
        self._x: FloatArray = rows[k.BUF_X]
        self._p: FloatArray = rows[k.BUF_P : k.BUF_P + 6]
        self._q: FloatArray = rows[k.BUF_Q : k.BUF_Q + 6]
        # The kernel leaves the residuals in the last row of the measurement block.
        self._residuals: FloatArray = rows[k.BUF_MEAS + 2]
        # x and P as saved by the online step (before it), kept by _record.
        self._saved: FloatArray = buf[_SAVED]
        # (first component, count, gate, residual slice) of each online measurement kind.
        self._kinds: dict[str, tuple[int, int, float, slice]] = {
            kind: (first, count, float(self._gates[count]), slice(first, first + count))
            for kind, (first, count) in _KIND_COMPONENTS.items()
        }
        # The odometry fast path's gate and residual view, looked up once.
        self._odometry_gate = self._kinds["odometry"][2]
        self._odometry_residual: FloatArray = self._residuals[self._kinds["odometry"][3]]

    def __reduce__(self) -> tuple[Any, ...]:
        # The estimate lives in one buffer updated in place, with x, P and Q views into
        # it: copies (copy.copy too) and pickles get their own buffer and views. A
        # subclass is rebuilt as itself, with what it adds restored after (see
        # extra_state).
        cls = type(self)
        if self._history:
            # A copy made during a call of this filter (a signal handler's, another
            # thread's) takes the buffer as that call left it, which the steps kept
            # may not match yet (a step taken, not yet kept): it keeps none, as after
            # an interrupted call. A short call under way itself (the one-call
            # guard's token): another thread's call meanwhile is refused, rather
            # than change the buffer or the steps between their two reads.
            callers = self._callers
            token = (get_ident(), "__reduce__", object())
            try:
                callers.append(token)
                # A call writing the buffer runs only as the first token and stays first
                # until it returns; another copy first only reads, and this one keeps the
                # steps (the second of two threads' copies taken at once kept none;
                # review 54, FRESH3's finding, as FieldDStar's c861d30).
                busy = callers[0][1] != "__reduce__"
                # The anchor with the buffer, no call between (see _reset's stores): read
                # after a call, a reset landing there (a signal handler's, another
                # thread's once the token was out) gave the copy the old buffer at the
                # new anchor, off by the anchors' difference (review 38).
                anchor = self._anchor
                buf = self._buf.copy()
                # The entries' arrays are never written after they are made: a copy
                # may share them.
                steps = [] if busy else self._steps[self._head :]
            finally:
                callers.remove(token)
        else:
            anchor = self._anchor  # with the buffer, no call between (see above)
            buf = self._buf.copy()
            steps = self._steps[self._head :]
        if buf[BUF_UNDO] != 0.0:
            # Made between a step to be undone (a time gap's overflowed prediction, a
            # lost positive definiteness) and its undo: the copy is the filter as
            # before that step (kept as it was, its next step clears the mark and
            # goes on from the overflowed state; see _settle).
            undo_step(buf)
        kept = (self._history, steps)
        args = (buf, self._gates.copy(), cls, anchor, kept)
        if cls is PlanarFusion:
            return _restore_fusion, args
        return _restore_fusion, args, extra_state(self, below=PlanarFusion)

    def __setstate__(self, state: Any) -> None:
        """Restore what a subclass adds; migrate a pickle made before the filter reduced itself.

        Pickles made before 1efa428 (1 December 2026) hold the filter's slots of
        then, Python's default state: loading one raised AttributeError (``_t``,
        a slot gone) or left the filter without slots of today (``_history``,
        at its first call). Their estimate, process noise, gates and time are
        taken into a filter as :class:`PlanarFusion` would build it (its x and y
        anchored, no step kept), which steps on from there. A subclass's own
        attributes (the state its pickles add) are restored as Python would.
        """
        instance, slots = state if isinstance(state, tuple) else (None, state)
        if slots and {"_x", "_p", "_q", "_gates"} <= slots.keys():
            if "_t" in slots:  # before the filter time moved into the buffer (f96b926)
                t = slots["_t"]
            else:
                t = float(np.asarray(slots["_buf"], dtype=np.float64).reshape(-1)[k.BUF_TIME])
            x = np.array(slots["_x"], dtype=np.float64).reshape(6)
            q = np.array(slots["_q"], dtype=np.float64).reshape(6, 6)
            t0 = None if t is None or math.isnan(t) else float(t)
            buf, anchor = _start_buffer(x, slots["_p"], t0, q=q)
            self._adopt(buf, np.array(slots["_gates"], dtype=np.float64).reshape(5), anchor)
            # What a subclass added (its __dict__, its slots) as Python restores it: the
            # migration dropped it (review 52, FRESH).
            added = {name: value for name, value in slots.items() if name not in _OLD_SLOTS}
            restore_slots(self, (instance, added))
            return
        if instance:
            self.__dict__.update(instance)
        for name, value in (slots or {}).items():
            object.__setattr__(self, name, value)

    @property
    def _entries(self) -> list[_Entry]:
        """The steps kept for ``history``, oldest first (a new list)."""
        return self._steps[self._head :]

    @property
    def history(self) -> float:
        """How far back (s) before the filter time a late measurement is still fused.

        The ``history`` given (0: measurements are taken in stamp order only).
        """
        return self._history

    @property
    def t(self) -> float | None:
        """Filter time, s; None before the first measurement when no ``t0`` was given."""
        t = float(self._buf[BUF_TIME])
        return None if math.isnan(t) else t

    @property
    def x(self) -> FloatArray:
        """Current state estimate ``[x, y, θ, v, ω, a]`` (6,), a copy."""
        out = np.array(self._x, dtype=np.float64, copy=True)
        ax, ay = self._anchor
        if ax or ay:
            out[0] += ax
            out[1] += ay
        return out

    @property
    def pose(self) -> Pose2D:
        """Current pose estimate."""
        ax, ay = self._anchor
        x = float(self._x[0])
        y = float(self._x[1])
        if ax or ay:
            x += ax
            y += ay
        return Pose2D(x, y, float(self._x[2]))

    def reset(
        self,
        x0: ArrayLike | None = None,
        P0: ArrayLike | None = None,
        *,
        t0: float | None = None,
        pose: Pose2D | ArrayLike | None = None,
    ) -> None:
        """Restart the filter from a given state and time (robot_localization's ``set_pose``).

        The filter becomes the one the constructor would build from these
        arguments with its own ``process_noise``, ``gate_probability`` and
        ``history``: later measurements give the same numbers, bit for bit.
        The steps kept for ``history`` are dropped (a late measurement older
        than ``t0`` is refused), and so is everything the previous estimate
        left (its time among it).

        Parameters
        ----------
        x0 : array_like, shape (6,), optional
            New state ``[x, y, yaw, v, omega, a]`` (finite); default zeros, as
            in the constructor (not the filter's first ``x0``).
        P0 : array_like, shape (6, 6) or (6,), optional
            New covariance (or its diagonal), positive definite, entries of
            magnitude at most 1e100; default ``diag(1e-9, 1e-9, 1e-9, 1, 1, 1)``.
        t0 : float, optional
            Time of the new state, s; without it the next measurement sets the
            clock (no prediction), as after a constructor without ``t0``.
        pose : Pose2D or array_like (x, y, theta), optional
            The new pose alone, keyword-only: ``x0`` with zero rates. Not with
            ``x0``.

        Raises
        ------
        TypeError, ValueError
            As the constructor, naming the argument; the filter is then
            unchanged.
        RuntimeError
            With ``history``, another call of this filter is under way (another
            thread's, or a signal handler's in the same thread): one call at a
            time, see the class notes; the filter is unchanged.

        Examples
        --------
        >>> fusion = PlanarFusion(t0=0.0, history=0.5)
        >>> _ = fusion.update_odometry(0.1, 1.0, 0.0, v_variance=1e-4, omega_variance=1e-4)
        >>> fusion.reset(pose=(2.0, 1.0, 0.5), t0=10.0)  # e.g. a localisation fix
        >>> fusion.t, fusion.pose
        (10.0, Pose2D(x=2.0, y=1.0, theta=0.5))
        >>> fusion.update_yaw(9.9, 0.5, variance=1e-3).status.name  # before the reset
        'OUT_OF_ORDER'
        """
        if self._history:
            self._one_at_a_time("reset", self._reset, x0, P0, t0, pose)
        else:
            self._reset(x0, P0, t0, pose)

    def _reset(
        self,
        x0: ArrayLike | None,
        P0: ArrayLike | None,
        t0: float | None,
        pose: Pose2D | ArrayLike | None,
    ) -> None:
        """:meth:`reset`'s work."""
        x = _start_state(x0, pose)
        buf, anchor = _start_buffer(x, P0, t0, q=self._q.copy())
        # Five stores, no call between (not even np.copyto's Python dispatcher): Python
        # delivers an interrupt at calls and loops only, so an interrupted reset has
        # happened or not. The buffer stays the same object: x, P and Q stay its views.
        # The one store that allocates (numpy's slice view), and so could fail, goes
        # first; the list and the slack's scale are made before it.
        entries: list[_Entry] = []
        age_scale = abs(buf.item(_BUF_ORIGIN)) + self._history
        self._buf[:] = buf
        self._anchor = anchor
        self._steps = entries
        self._head = 0
        self._age_scale = age_scale

    def predict(self, t: float) -> None:
        """Propagate the state to time ``t`` (s) without a measurement.

        Parameters
        ----------
        t : float
            Time to predict to, s: finite and not older than the filter time
            (before the first measurement without ``t0`` it only sets the clock).

        Raises
        ------
        TypeError
            If ``t`` is not a real number (a bool, a string, None).
        ValueError
            If ``t`` is not finite, is a time float64 would round (see the
            class notes) or is older than the filter time.
        FilterError
            If the prediction would overflow float64 (a huge time gap); the
            filter is unchanged.
        RuntimeError
            With ``history``, another call of this filter is under way (another
            thread's, or a signal handler's in the same thread): one call at a
            time, see the class notes; the filter is unchanged.

        Notes
        -----
        The prediction is kept: the filter time becomes ``t``, so a measurement
        stamped before ``t`` is then refused (``OUT_OF_ORDER``) unless
        ``history`` reaches back to it. To publish the estimate on a timer at
        the current time (robot_localization's ``frequency``), predict a copy,
        ``copy.copy(fusion).predict(now)``, or give the filter ``history``:
        messages arrive after their stamps, so predicting the filter itself
        at each tick makes them late. On robot_localization's test1 bag
        (IMU stamps 21-36 ms behind arrival), fed in arrival order with a
        30 Hz timer, predicting the filter refused 19,411 of the 27,682
        readings and ended 55 m from the stamp-ordered run; predicting a copy,
        6,154 (those late on arrival) and 2 mm; with ``history=0.2``, none
        and 3 mm (review 46).

        Examples
        --------
        >>> fusion = PlanarFusion([0.0, 0.0, 0.0, 1.0, 0.5, 0.0], t0=0.0)  # 1 m/s, 0.5 rad/s
        >>> fusion.predict(0.5)
        >>> fusion.t, fusion.pose  # 0.5 m along the mid-step heading 0.125 rad
        (0.5, Pose2D(x=0.4960..., y=0.0623..., theta=0.25))
        >>> fusion.P.diagonal().round(3)  # the uncertainty grew
        array([0.287, 0.045, 0.28 , 1.262, 1.01 , 1.005])

        An estimate for a timer tick at 0.6 s, the filter left as it was, so a
        message stamped 0.55 s that arrives after the tick is still fused:

        >>> import copy
        >>> ahead = copy.copy(fusion)
        >>> ahead.predict(0.6)
        >>> ahead.t, fusion.t
        (0.6, 0.5)
        >>> fusion.update_speed(0.55, 1.0, variance=1e-4).accepted
        True
        """
        # With history, as the filter's one call under way: _one_at_a_time written out,
        # its token made only then (0.03 µs without history, where a call cost 0.04).
        history = self._history
        token = None
        try:
            if history:
                token = (get_ident(), "predict", object())
                self._callers.append(token)
                if self._callers[0] is not token:
                    raise RuntimeError(_in_use(type(self).__name__, "predict", self._callers[0]))
            time = as_time(t, "t")
            # The buffer's time, not the t property, which a subclass may override.
            last = float(self._buf[BUF_TIME])
            if math.isnan(last):  # the clock is not set
                self._buf[BUF_TIME] = time
                self._set_origin(time)
                return
            if time < last:
                raise ValueError(f"t={time} s is older than the filter time {last} s")
            # The online step without a measurement (count 0): compiled once with the
            # updates.
            status = 0  # for _settle: unknown until the step returns
            try:
                status, _ = _step(self._buf, time, *_PREDICT)
                if status == TIME_GAP:
                    undo_step(self._buf)  # under the try: an interrupt on entering it
                # A step too: a late measurement goes before it. Not one to the newest
                # stamp kept: no time passed, it changed nothing, and kept there it would
                # come before the steps of its stamp already taken (see _TIE_RANKS).
                elif history and not (self._steps and self._steps[-1][0] == time):
                    self._record(time, _PREDICT, "predict")
            except BaseException:
                self._settle(status)
                raise
            if status == TIME_GAP:
                raise FilterError(
                    f"predicting over the time gap of {time - last} s overflows float64; "
                    "the filter is unchanged"
                )
        finally:
            if token is not None:
                self._callers.remove(token)

    def update_odometry(
        self, t: float, v: float, omega: float, *, v_variance: float, omega_variance: float
    ) -> UpdateResult:
        """Fuse a wheel-odometry twist: forward speed ``v`` (m/s), yaw rate ``omega`` (rad/s).

        Parameters
        ----------
        t : float
            Time of the measurement, s.
        v : float
            Measured forward speed, m/s.
        omega : float
            Measured yaw rate, rad/s.
        v_variance, omega_variance : float
            Their variances, (m/s)² and (rad/s)², in [1e-100, 1e100]
            (keyword-only).

        Returns
        -------
        UpdateResult
            Whether the measurement was applied (``accepted``; an out-of-order,
            gated or overflowing one is not, with the ``reason``), its NIS and
            its residual ``[v - v̂, ω - ω̂]`` (m/s, rad/s), shape (2,).

        Raises
        ------
        TypeError, ValueError
            A time or value that is not a finite real number, a time float64
            would round (an integer beyond 2**53, a float32 coarser than 1 ms:
            see the class notes) or a variance outside [1e-100, 1e100], naming
            it; the filter is unchanged.
        FilterError
            The prediction to ``t`` would overflow float64 (a huge time gap) or
            the update would lose positive definiteness; the filter is unchanged.
        RuntimeError
            With ``history``, another call of this filter is under way (another
            thread's, or a signal handler's in the same thread): one call at a
            time, see the class notes; the filter is unchanged.

        Examples
        --------
        >>> fusion = PlanarFusion(t0=0.0)  # at rest, speed and yaw rate unknown (variance 1)
        >>> result = fusion.update_odometry(0.1, 1.0, 0.2, v_variance=0.01, omega_variance=0.01)
        >>> result.accepted, result.residual
        (True, array([1. , 0.2]))
        >>> fusion.x[3:5].round(3)  # v and ω pulled almost to the measurement
        array([0.99 , 0.198])
        """
        # Fast path (the call runs at the odometry rate): the arguments go straight to
        # the compiled step, whose entry takes anything but a float (a NumPy float64 or
        # an exact int counts as one) as NaN (a check in C: five type() tests in Python
        # cost about 70 ns) and which checks the rest (finite values, variances in range,
        # a running clock, an in-order time), returning INVALID, changing nothing, if any
        # check fails; then, and so for anything but floats, the general way validates
        # and explains.
        if not self._history:
            status = 0  # for _settle: unknown until the step returns
            try:
                status, nis = _step(
                    self._buf, t, 1, 2, v, omega, v_variance, omega_variance, self._odometry_gate
                )
                if status and status != INVALID:  # undone under the try (see _settle)
                    # As floats, as the step took them (an int or NumPy float64 too).
                    return self._not_applied(
                        status, "odometry", float(t), nis, slice(1, 3),
                        (1, 2, float(v), float(omega), float(v_variance),
                         float(omega_variance), self._odometry_gate),
                    )  # fmt: skip
            except BaseException:
                self._settle(status)
                raise
            if not status:
                # new_result(True, nis, residual, None), written out: this saves a call.
                result = _Building()
                result.accepted = True
                result.nis = nis
                result.residual = self._odometry_residual.copy()
                result.reason = None
                result.__class__ = UpdateResult  # type: ignore[assignment]
                return result  # type: ignore[return-value]
            return self._apply(
                t, "odometry", v, omega, v_variance, omega_variance, _ODOMETRY_NAMES, tried=True
            )
        # With history: the same fast path, keeping the step, as the filter's one call
        # under way (_one_at_a_time written out: through it and _apply the check cost
        # 0.9 µs, half a step kept; here about 0.2 µs).
        callers = self._callers
        token = (get_ident(), "update_odometry", object())
        try:
            callers.append(token)
            if callers[0] is not token:
                raise RuntimeError(_in_use(type(self).__name__, "update_odometry", callers[0]))
            # A stamp equal to the newest step kept (rare) goes the general way: it may
            # belong before that step (see _TIE_RANKS); compared once known to be a float.
            if type(t) is float and not (self._steps and self._steps[-1][0] == t):
                status = 0  # for _settle: unknown until the step returns
                try:
                    status, nis = _step(
                        self._buf, t, 1, 2, v, omega, v_variance, omega_variance,
                        self._odometry_gate,
                    )  # fmt: skip
                    if status:
                        if status != INVALID:  # undone under the try (see _settle)
                            return self._not_applied(
                                status, "odometry", t, nis, slice(1, 3),
                                (1, 2, float(v), float(omega), float(v_variance),
                                 float(omega_variance), self._odometry_gate),
                            )  # fmt: skip
                    else:  # under the try: interrupted, the history is dropped
                        args = (1, 2, float(v), float(omega), float(v_variance),
                                float(omega_variance), self._odometry_gate)  # fmt: skip
                        self._record(t, args, "odometry")
                except BaseException:
                    self._settle(status)
                    raise
                if not status:
                    return new_result(True, nis, self._odometry_residual.copy(), None)
            return self._apply(
                t, "odometry", v, omega, v_variance, omega_variance, _ODOMETRY_NAMES,
                tried=True, held=True,
            )  # fmt: skip
        finally:
            callers.remove(token)

    def update_speed(self, t: float, v: float, *, variance: float) -> UpdateResult:
        """Fuse a forward speed ``v`` (m/s) alone; ``variance`` in (m/s)², keyword-only.

        For odometry whose yaw rate is unreliable (skid-steer robots).

        Parameters
        ----------
        t : float
            Time of the measurement, s.
        v : float
            Measured forward speed, m/s.
        variance : float
            Its variance, (m/s)², in [1e-100, 1e100] (keyword-only).

        Returns
        -------
        UpdateResult
            Whether the measurement was applied (``accepted``; an out-of-order,
            gated or overflowing one is not, with the ``reason``), its NIS and
            its residual ``[v - v̂]`` (m/s), shape (1,).

        Raises
        ------
        TypeError, ValueError
            A time or value that is not a finite real number, a time float64
            would round (an integer beyond 2**53, a float32 coarser than 1 ms:
            see the class notes) or a variance outside [1e-100, 1e100], naming
            it; the filter is unchanged.
        FilterError
            The prediction to ``t`` would overflow float64 (a huge time gap) or
            the update would lose positive definiteness; the filter is unchanged.
        RuntimeError
            With ``history``, another call of this filter is under way (another
            thread's, or a signal handler's in the same thread): one call at a
            time, see the class notes; the filter is unchanged.

        Examples
        --------
        >>> fusion = PlanarFusion(t0=0.0)  # at rest, speed unknown (variance 1)
        >>> fusion.update_speed(0.1, 1.0, variance=0.01).residual
        array([1.])
        >>> fusion.x[3:5].round(3)  # v pulled to the measurement, ω untouched
        array([0.99, 0.  ])
        """
        return self._apply(t, "speed", v, 0.0, variance, 1.0, ("v", "", "variance", ""))

    def update_yaw(self, t: float, yaw: float, *, variance: float) -> UpdateResult:
        """Fuse an absolute yaw ``yaw`` (rad, any range; compass or IMU); ``variance`` in rad².

        Parameters
        ----------
        t : float
            Time of the measurement, s.
        yaw : float
            Measured heading, rad, counter-clockwise from the world x axis; any
            finite value (the residual is wrapped to (-π, π]).
        variance : float
            Its variance, rad², in [1e-100, 1e100] (keyword-only).

        Returns
        -------
        UpdateResult
            Whether the measurement was applied (``accepted``; an out-of-order,
            gated or overflowing one is not, with the ``reason``), its NIS and
            its residual ``[wrap(yaw - θ̂)]`` (rad), shape (1,).

        Raises
        ------
        TypeError, ValueError
            A time or value that is not a finite real number, a time float64
            would round (an integer beyond 2**53, a float32 coarser than 1 ms:
            see the class notes) or a variance outside [1e-100, 1e100], naming
            it; the filter is unchanged.
        FilterError
            The prediction to ``t`` would overflow float64 (a huge time gap) or
            the update would lose positive definiteness; the filter is unchanged.
        RuntimeError
            With ``history``, another call of this filter is under way (another
            thread's, or a signal handler's in the same thread): one call at a
            time, see the class notes; the filter is unchanged.

        Examples
        --------
        >>> fusion = PlanarFusion([0.0, 0.0, 3.1, 0.0, 0.0, 0.0], [1e-9, 1e-9, 1.0, 1.0, 1.0, 1.0],
        ...                       t0=0.0)  # heading 3.1 rad, variance 1 rad²
        >>> fusion.update_yaw(0.0, -3.1, variance=0.01).residual.round(4)  # across ±π
        array([0.0832])
        >>> round(fusion.pose.theta, 4)  # moved past π, wrapped
        -3.1008
        """
        return self._apply(t, "yaw", yaw, 0.0, variance, 1.0, ("yaw", "", "variance", ""))

    def update_yaw_rate(self, t: float, omega: float, *, variance: float) -> UpdateResult:
        """Fuse a gyro yaw rate ``omega`` (rad/s); ``variance`` in (rad/s)², keyword-only.

        Parameters
        ----------
        t : float
            Time of the measurement, s.
        omega : float
            Measured yaw rate, rad/s, counter-clockwise positive.
        variance : float
            Its variance, (rad/s)², in [1e-100, 1e100] (keyword-only).

        Returns
        -------
        UpdateResult
            Whether the measurement was applied (``accepted``; an out-of-order,
            gated or overflowing one is not, with the ``reason``), its NIS and
            its residual ``[ω - ω̂]`` (rad/s), shape (1,).

        Raises
        ------
        TypeError, ValueError
            A time or value that is not a finite real number, a time float64
            would round (an integer beyond 2**53, a float32 coarser than 1 ms:
            see the class notes) or a variance outside [1e-100, 1e100], naming
            it; the filter is unchanged.
        FilterError
            The prediction to ``t`` would overflow float64 (a huge time gap) or
            the update would lose positive definiteness; the filter is unchanged.
        RuntimeError
            With ``history``, another call of this filter is under way (another
            thread's, or a signal handler's in the same thread): one call at a
            time, see the class notes; the filter is unchanged.

        Examples
        --------
        >>> fusion = PlanarFusion(t0=0.0)  # at rest, yaw rate unknown (variance 1)
        >>> result = fusion.update_yaw_rate(0.1, 0.5, variance=1e-4)
        >>> result.accepted, result.residual, round(float(fusion.x[4]), 3)
        (True, array([0.5]), 0.5)
        """
        return self._apply(t, "yaw_rate", omega, 0.0, variance, 1.0, ("omega", "", "variance", ""))

    def update_acceleration(self, t: float, a: float, *, variance: float) -> UpdateResult:
        """Fuse a forward acceleration ``a`` (m/s², gravity removed); ``variance`` in (m/s²)².

        Parameters
        ----------
        t : float
            Time of the measurement, s.
        a : float
            Measured forward acceleration, m/s², gravity removed.
        variance : float
            Its variance, (m/s²)², in [1e-100, 1e100] (keyword-only).

        Returns
        -------
        UpdateResult
            Whether the measurement was applied (``accepted``; an out-of-order,
            gated or overflowing one is not, with the ``reason``), its NIS and
            its residual ``[a - â]`` (m/s²), shape (1,).

        Raises
        ------
        TypeError, ValueError
            A time or value that is not a finite real number, a time float64
            would round (an integer beyond 2**53, a float32 coarser than 1 ms:
            see the class notes) or a variance outside [1e-100, 1e100], naming
            it; the filter is unchanged.
        FilterError
            The prediction to ``t`` would overflow float64 (a huge time gap) or
            the update would lose positive definiteness; the filter is unchanged.
        RuntimeError
            With ``history``, another call of this filter is under way (another
            thread's, or a signal handler's in the same thread): one call at a
            time, see the class notes; the filter is unchanged.

        Examples
        --------
        >>> fusion = PlanarFusion(t0=0.0)  # at rest, acceleration unknown (variance 1)
        >>> result = fusion.update_acceleration(0.1, 2.0, variance=0.01)
        >>> result.accepted, result.residual, round(float(fusion.x[5]), 2)
        (True, array([2.]), 1.98)
        """
        return self._apply(t, "acceleration", a, 0.0, variance, 1.0, ("a", "", "variance", ""))

    def _apply(
        self,
        t: Any,
        kind: str,
        z0: Any,
        z1: Any,
        var0: Any,
        var1: Any,
        names: tuple[str, str, str, str],
        *,
        tried: bool = False,
        held: bool = False,
    ) -> UpdateResult:
        """Fuse a measurement of ``kind``: the fast path, unless ``tried`` (the caller's
        own fast path returned INVALID, which this one would too), then the general way.

        With ``history``, as the filter's one call under way (see :meth:`_one_at_a_time`),
        unless ``held``: the caller made it so.
        """
        first, count, gate, comps = self._kinds[kind]
        if self._history:
            if not held:  # held: the caller holds the call (only with tried)
                # The fast path keeping the step, as the filter's one call under way
                # (_one_at_a_time written out, see update_odometry); the rest the general way.
                name = "update_" + kind
                callers = self._callers
                token = (get_ident(), name, object())
                try:
                    callers.append(token)
                    if callers[0] is not token:
                        raise RuntimeError(_in_use(type(self).__name__, name, callers[0]))
                    if not tried and type(t) is float and not (
                        self._steps and self._steps[-1][0] == t
                    ):
                        status = 0  # for _settle: unknown until the step returns
                        try:
                            status, nis = _step(
                                self._buf, t, first, count, z0, z1, var0, var1, gate
                            )
                            if status:
                                if status != INVALID:  # undone under the try (see _settle)
                                    args = (first, count, float(z0), float(z1), float(var0),
                                            float(var1), gate)  # fmt: skip
                                    return self._not_applied(status, kind, t, nis, comps, args)
                            else:  # under the try: interrupted, the history is dropped
                                args = (first, count, float(z0), float(z1), float(var0),
                                        float(var1), gate)  # fmt: skip
                                self._record(t, args, kind)
                        except BaseException:
                            self._settle(status)
                            raise
                        if not status:
                            return new_result(True, nis, self._residuals[comps].copy(), None)
                    return self._apply(t, kind, z0, z1, var0, var1, names, tried=True, held=True)
                finally:
                    callers.remove(token)
        elif not tried:
            # Fast path: the arguments go straight to the compiled step, which takes
            # anything but a float as NaN and checks the rest.
            status = 0  # for _settle: unknown until the step returns
            try:
                status, nis = _step(self._buf, t, first, count, z0, z1, var0, var1, gate)
                if status and status != INVALID:  # undone under the try (see _settle)
                    # As floats, as the step took them (an int or NumPy float64 too).
                    args = (first, count, float(z0), float(z1), float(var0), float(var1), gate)
                    return self._not_applied(status, kind, float(t), nis, comps, args)
            except BaseException:
                self._settle(status)
                raise
            if not status:
                return new_result(True, nis, self._residuals[comps].copy(), None)
        t = as_time(t, "t")
        z0 = finite_float(z0, names[0])
        var0 = variance(var0, names[2])
        if names[1]:
            z1 = finite_float(z1, names[1])
            var1 = variance(var1, names[3])
        args = (first, count, z0, float(z1), var0, float(var1), gate)
        # The buffer's time, not the t property, which a subclass may override.
        last = float(self._buf[BUF_TIME])
        unset = math.isnan(last)
        if unset:
            # The first measurement sets the clock (no prediction: the step's dt is 0).
            self._buf[BUF_TIME] = t
        elif t <= last and self._history and (t < last or self._goes_before(t, args)):
            return self._rewind(t, kind, args, comps, last)
        elif t < last:
            return rejected_result(
                math.nan,
                np.empty(0),
                f"out of order: t={t} s is older than the filter time {last} s",
                FusionStatus.OUT_OF_ORDER,
            )
        status = 0  # for _settle: unknown until the step returns
        try:
            status, nis = _step(self._buf, t, *args)
            if status:  # undone under the try (see _settle)
                if unset:
                    # Before the step the clock was not set: undone, it is not set either.
                    self._buf[BUF_SAVED_TIME] = math.nan
                return self._not_applied(status, kind, t, nis, comps, args)
            if self._history:  # under the try: interrupted, the history is dropped
                self._record(t, args, kind, unset=unset)
        except BaseException:
            self._settle(status)
            raise
        return new_result(True, nis, self._residuals[comps].copy(), None)

    def _one_at_a_time(
        self, name: str, call: Callable[..., _R], /, *args: Any, **kwargs: Any
    ) -> _R:
        """Run ``call`` (the work of the method ``name``) as the filter's one call under way.

        For a filter with ``history`` only: a call made while another runs (another
        thread's, or a signal handler's in the same thread) raises ``RuntimeError``
        and changes nothing, as :func:`navkit._shared.locks.one_caller`'s guard (the
        same tokens in ``_callers``, the same messages). Two calls at once otherwise
        corrupted the steps kept without an error: a handler's update between the
        main thread's step and its record kept the steps out of time order, and one
        during a late measurement's replay was overwritten by the replayed buffer.
        Without ``history`` the calls are not checked (see the class notes). The
        updates and :meth:`predict` write it out (0.2 µs, where this call cost 0.5).
        """
        callers = self._callers
        # Unequal to every other token (its object): a refused call of the same method
        # in the same thread (a signal handler's) takes out its own, not the runner's.
        token = (get_ident(), name, object())
        try:
            callers.append(token)
            if callers[0] is not token:
                raise RuntimeError(_in_use(type(self).__name__, name, callers[0]))
            return call(*args, **kwargs)
        finally:
            callers.remove(token)

    def _settle(self, status: int) -> None:
        """Undo a step left overflowed or to be undone by an exception raised part-way.

        Python delivers a ``KeyboardInterrupt`` as a call returns: one delivered
        as the online step returned loses its status. The step marks one to be
        undone in the buffer (``BUF_UNDO``, cleared by :func:`undo_step`): a
        ``TIME_GAP`` (the overflowed prediction, also found by its non-finite
        entries) or a ``NOT_POSITIVE_DEFINITE``, which keeps a finite
        prediction that the state alone cannot tell from a gated step's. The
        callers also run their :func:`undo_step` under the same try:
        one is delivered on entering a Python function too (``_not_applied``,
        ``undo_step``), with the ``status`` of the step when it was known (0
        if not): a step to be undone (``TIME_GAP``, ``NOT_POSITIVE_DEFINITE``)
        is undone again here, whether its undo had begun or not (undoing is
        idempotent); ``undo_step`` puts the time back before ``x`` and ``P``.

        The steps kept for ``history`` are dropped (later late measurements
        are refused, as after :meth:`update_batch`): an interrupt may have come
        between a step and its record. Not for a :class:`FilterError`, raised
        with the filter as before the call and nothing recorded.
        """
        if (
            status in (TIME_GAP, NOT_POSITIVE_DEFINITE)
            or self._buf[BUF_UNDO] != 0.0
            or not (np.isfinite(self._x).all() and np.isfinite(self._p).all())
        ):
            undo_step(self._buf)
        if not isinstance(sys.exception(), FilterError):
            # A new list, not clear(): two stores without a call between (see reset),
            # where a list cleared in place and interrupted keeps _head past its end.
            self._steps = []
            self._head = 0

    def _record(self, t: float, args: _StepArgs, kind: str, *, unset: bool = False) -> None:
        """Keep the online step just taken at ``t`` for ``history``; forget the old ones.

        The step left x, P and the time from before it in the buffer's saved
        block; ``unset``: the clock was not set before it. A step at ``t_i``
        is needed only to fuse a measurement older than ``t_i``, and one is
        fused while its age ``t - stamp`` is at most ``history``, give or take
        :meth:`_rewind`'s slack (:data:`_AGE_RTOL`): steps older than that,
        slack included (:data:`_TRIM_RTOL`), go. Without the slack, a step of
        the measurement's own stamp whose age rounded above ``history`` went,
        and the measurement, taken, was fused after it where the tie order
        puts it before (review 27: late odometry at 0.7 s after the yaw update
        at 0.7 s, ``history=0.3`` at 1.0 s). A step that set the clock sets its
        origin (:data:`_BUF_ORIGIN`), the slack's scale.
        """
        before = math.nan if unset else self._buf.item(BUF_SAVED_TIME)
        if before != before:  # NaN: this step set the clock (also a gated first step)
            self._set_origin(t)
        steps = self._steps
        steps.append((t, before, self._saved.copy(), args, kind))
        history = self._history
        head = self._head
        age = t - steps[head][0]
        if age > history:
            # Past the window with _too_old's slack for any stamp (see _TRIM_RTOL),
            # computed once a call (35 ns, where _too_old step by step cost 80).
            limit = history + _TRIM_RTOL * ((t if t > 0.0 else -t) + self._age_scale)
            if age > limit:
                # Each step goes once: about one a call. The loop stops at the
                # step just kept (age 0).
                n = head + 1
                while t - steps[n][0] > limit:
                    n += 1
                self._head = n
                # Deleting the steps gone shifted the whole list, every call: O(window)
                # a call (21 µs at 1 kHz with a 256 s window). Their slots are dropped
                # once they are half the list, a shift per window's worth of calls.
                while head < n:
                    steps[head] = _GONE
                    head += 1
                if n > len(steps) >> 1:
                    del steps[:n]
                    self._head = 0

    def _set_origin(self, t: float) -> None:
        """Take ``t``, where the clock was just set, as its origin (:data:`_BUF_ORIGIN`)."""
        age_scale = abs(t) + self._history
        self._buf[_BUF_ORIGIN] = t
        self._age_scale = age_scale

    def _goes_before(self, t: float, args: _StepArgs) -> bool:
        """Whether a step at the filter time ``t`` belongs before the newest kept step.

        True when that step has the stamp ``t`` and comes later in the tie
        order (:data:`_TIE_RANKS`): the step is then fused as a late one.
        """
        entries = self._steps
        return bool(entries) and entries[-1][0] == t and (
            _tie_rank(entries[-1][3]) > _tie_rank(args)
        )

    def _rewind(
        self, t: float, kind: str, args: _StepArgs, comps: slice, last: float
    ) -> UpdateResult:
        """Fuse a measurement older than the filter time ``last``, within ``history``.

        As robot_localization's ``smooth_lagged_data``: back to the state kept
        before the first step later than ``t``, the measurement fused there, and
        the later steps taken again, in stamp order; the steps of its own stamp
        are in the tie order of :data:`_TIE_RANKS` (one kind in the order it
        came), as in the batch of :meth:`MeasurementLog.from_streams`. On a
        copy of the buffer, which becomes the filter's in one C call at the end:
        refused, raising or interrupted before that, the filter is unchanged.
        """
        entries = self._steps
        head = self._head  # the steps kept are entries[head:]
        i = bisect_right(entries, t, lo=head, key=_entry_time)
        if i > head and entries[i - 1][0] == t:  # a tie: before those later in tie order
            rank = _tie_rank(args)
            while i > head and entries[i - 1][0] == t and _tie_rank(entries[i - 1][3]) > rank:
                i -= 1
        # entries[i][1] is NaN where the clock was not set before that step: any t goes.
        # The age, not t < last - history: 1.0 - 0.7 rounds up to 0.30000000000000004,
        # which refused a measurement at 0.3 s, 0.7 s before 1.0 s (1.0 - 0.3 is 0.7);
        # and with a slack for the stamps' rounding, which refused one at 0.7 s with
        # history=0.3 (see _AGE_RTOL).
        origin = self._buf.item(_BUF_ORIGIN)
        if _too_old(last, t, self._history, origin) or i == len(entries) or entries[i][1] > t:
            return rejected_result(
                math.nan,
                np.empty(0),
                f"out of order: t={t} s is older than the filter time {last} s and "
                f"the history (history={self._history} s) does not reach back to it",
                FusionStatus.OUT_OF_ORDER,
            )
        _, before, state, _, _ = entries[i]
        trial = self._buf.copy()
        trial[_STATE] = state
        trial[BUF_TIME] = before
        new: list[_Entry] = []
        status, nis = self._replay(trial, t, args, kind, new)
        residual = trial[_RESIDUALS][comps].copy()
        # The later steps, as _replay takes them, written out (the loop runs once per
        # step kept after t: a second of 250 Hz streams is 250 steps).
        step = _step
        saved = trial[_SAVED]  # a view, copied for each step kept
        for ti, _, _, step_args, step_kind in entries[i:]:
            before = trial.item(BUF_TIME)  # set: the first step set the clock
            code = step(trial, ti, *step_args)[0]
            if code in (NOT_POSITIVE_DEFINITE, TIME_GAP):  # rare: the general way
                undo_step(trial)
                self._replay(trial, ti, step_args, step_kind, new)
            else:
                new.append((ti, before, saved.copy(), step_args, step_kind))
        try:
            np.copyto(self._buf, trial)  # one C call: Python delivers no interrupt inside it
            entries[i:] = new
        except BaseException:  # between the two: the filter took the measurement
            self._steps = []  # and _head with it, no call between (see _settle)
            self._head = 0
            raise
        if not status:
            return new_result(True, nis, residual, None)
        return _rejection(status, nis, residual)

    @staticmethod
    def _replay(
        buf: FloatArray, t: float, args: _StepArgs, kind: str, new: list[_Entry]
    ) -> tuple[int, float]:
        """Take one step of :meth:`_rewind` on ``buf`` (as an online update would) and keep it.

        Raises :class:`~navkit.errors.FilterError` where the online update would.
        """
        before = float(buf[BUF_TIME])
        if math.isnan(before):  # no clock yet: this step sets it (no prediction)
            buf[BUF_TIME] = t
        status, nis = _step(buf, t, *args)
        if status == NOT_POSITIVE_DEFINITE:
            undo_step(buf)
            status, nis = _loaded_into(buf, t, args)
            if status == NOT_POSITIVE_DEFINITE:
                raise FilterError(
                    f"{kind} update at t={t} s, taken again after a late measurement: "
                    "covariance is not positive definite; the filter is unchanged"
                    + negative_eigenvalue_note(
                        buf.reshape(k.BUF_ROWS, k.W)[k.BUF_Q : k.BUF_Q + 6], "process_noise"
                    )
                )
        elif status == TIME_GAP:
            raise FilterError(
                f"{kind} update at t={t} s, taken again after a late measurement: "
                "the prediction overflows float64; the filter is unchanged"
            )
        new.append((t, before, buf[_SAVED].copy(), args, kind))
        return status, nis

    def _not_applied(
        self,
        status: int,
        kind: str,
        t: float,
        nis: float,
        comps: slice,
        args: _StepArgs,
    ) -> UpdateResult:
        """Raise or report a measurement the kernel did not apply (off the hot path).

        ``args`` are the step's arguments after the time: ``first``, ``count``,
        the values, the variances and the gate. Called under the step's try: a
        step that changed the filter is kept for ``history`` here.
        """
        if status in (NOT_POSITIVE_DEFINITE, TIME_GAP):
            undo_step(self._buf)  # the filter (and its time) as before the step
        if status == NOT_POSITIVE_DEFINITE:
            status, nis = _loaded_into(self._buf, t, args)
            if status == NOT_POSITIVE_DEFINITE:
                last = float(self._buf[BUF_TIME])
                # NaN: the clock was not set, so the measurement was not predicted to.
                after = (
                    "without a prediction (the first measurement)"
                    if math.isnan(last)
                    else f"after a prediction over {t - last:.6g} s"
                )
                raise FilterError(
                    f"{kind} update: covariance is not positive definite ({after}); "
                    "the filter is unchanged" + negative_eigenvalue_note(self._q, "process_noise")
                )
        if status == TIME_GAP:
            gap = t - float(self._buf[BUF_TIME])
            raise FilterError(
                f"{kind} update: predicting over the time gap of {gap} s to t={t} s overflows "
                "float64; the filter is unchanged"
            )
        if self._history:
            self._record(t, args, kind)
        if not status:
            return new_result(True, nis, self._residuals[comps].copy(), None)
        return _rejection(status, nis, self._residuals[comps].copy())

    def update_batch(self, log: MeasurementLog) -> FusionResult:
        """Fuse a whole :class:`MeasurementLog` in one compiled kernel call.

        Equivalent to calling the online updates row by row (same numbers), but
        without per-call overhead. The filter keeps the final state and time.
        Rows are taken in the log's order even with ``history``, and are not
        kept for it: online measurements older than the log's last row are
        refused afterwards (fuse a sorted log: :meth:`MeasurementLog.from_streams`).
        An empty log changes nothing, the history included.
        Instead of raising, a row is marked in ``FusionResult.status``
        (:class:`FusionStatus`): rows older than the filter time are skipped
        (``OUT_OF_ORDER``), and so are rows whose prediction would overflow
        float64 (``TIME_GAP``, e.g. a corrupt timestamp; the state and time stay
        as they were, and later rows continue from them); gated rows keep the
        prediction (``GATED``), and so does a row whose update would lose
        positive definiteness even from a loaded prediction (see the class
        notes; ``NOT_POSITIVE_DEFINITE``) or overflow
        (``OVERFLOW``). Every state and covariance in the result is finite.

        The result holds every row's state and covariance, about 350 bytes a
        row (1.3 GB for an hour of readings at 1 kHz). Fuse a longer log in
        pieces, each a :class:`MeasurementLog` of consecutive rows
        (``MeasurementLog(log.times[i:j], log.values[i:j], log.variances[i:j],
        log.observed[i:j])``): each call continues from the state the last
        left, and the final state is the same as from the whole log.

        Parameters
        ----------
        log : MeasurementLog
            Measurements, applied row by row in the log's order (see
            :meth:`MeasurementLog.from_streams` for a time-sorted log).

        Returns
        -------
        FusionResult
            State (T, 6), covariance (T, 6, 6), status (T,) and NIS (T,) after
            every row of the T in ``log`` (units as in :class:`FusionResult`);
            the state before the log is not a row (read :attr:`x` and
            :attr:`P` before the call for it).

        Raises
        ------
        TypeError
            If ``log`` is not a :class:`MeasurementLog`.
        RuntimeError
            With ``history``, another call of this filter is under way (another
            thread's, or a signal handler's in the same thread): one call at a
            time, see the class notes; the filter is unchanged.

        Examples
        --------
        >>> fusion = PlanarFusion(t0=0.0)
        >>> log = MeasurementLog.from_streams(  # 1 s of odometry at 1 m/s, 10 Hz
        ...     odometry=(np.arange(1, 11) * 0.1, np.ones(10), np.zeros(10)))
        >>> result = fusion.update_batch(log)
        >>> result.states.shape, bool(result.accepted.all()), round(result.final_pose.x, 3)
        ((10, 6), True, 1.0)
        >>> late = fusion.update_batch(MeasurementLog.from_streams(yaw=([0.5, 1.1], [0.0, 0.0])))
        >>> [FusionStatus(code).name for code in late.status]  # 0.5 s is before the filter time
        ['OUT_OF_ORDER', 'ACCEPTED']
        """
        if self._history:
            return self._one_at_a_time("update_batch", self._batch, log)
        return self._batch(log)

    def _batch(self, log: MeasurementLog) -> FusionResult:
        """:meth:`update_batch`'s work."""
        if not isinstance(log, MeasurementLog):
            raise TypeError(f"log must be a MeasurementLog, got {type(log).__name__}")
        n = len(log)
        out_x = np.empty((n, 6))
        out_p = np.empty((n, 6, 6))
        status = np.empty(n, dtype=np.int8)
        nis = np.empty(n)
        if n == 0:
            return _fusion_result(log.times, out_x, out_p, status, nis)
        # The log's rows are not kept for ``history``, nor the steps before them (a
        # new list and _head with it, no call between: see _settle).
        self._steps = []
        self._head = 0
        # The kernel undoes a TIME_GAP in row 0 from the last output row (see planar_run).
        out_x[-1] = self._x
        out_p[-1] = self._p
        if math.isnan(self._buf[BUF_TIME]):  # the clock starts at the first row
            self._set_origin(float(log.times[0]))
        variances = np.where(log.observed, log.variances, 0.0)
        # On a copy, put in place by one C call: the kernel runs without the GIL and
        # writes x and P row by row (the time at the end), so another thread's copy or
        # pickle of the filter's own buffer meanwhile took x, P and the time of
        # different rows, half a step among them (15,056 of 15,727 copies taken
        # during a 200,000-row log; review 53, FOUND6). Now it is the filter as
        # before the log.
        work = self._buf.copy()
        k.planar_run(
            work, log.times, log.values, variances, self._gates, out_x, out_p, status, nis,
            k.step_address(),
        )  # fmt: skip
        if (status == NOT_POSITIVE_DEFINITE).any():
            # The redo on the same copy: put in place before it, the kernel's first
            # result (neither the filter before nor after the log) was what a copy
            # taken during the redo's kernel calls, or an interrupt, left (review 54,
            # FOUND7).
            self._loaded_rows(work, log, variances, (out_x, out_p, status, nis))
        np.copyto(self._buf, work)
        ax, ay = self._anchor
        if ax or ay:
            out_x[:, 0] += ax
            out_x[:, 1] += ay
        return _fusion_result(log.times, out_x, out_p, status, nis)

    def _loaded_rows(
        self,
        buf: FloatArray,
        log: MeasurementLog,
        variances: FloatArray,
        outputs: tuple[FloatArray, FloatArray, NDArray[np.int8], FloatArray],
    ) -> None:
        """Redo the rows of a batch that lost positive definiteness, as the online updates do.

        Each such row kept its prediction: its update is redone from that
        prediction loaded (:func:`_load`, as :func:`_loaded_into`), and when it
        goes through, the rows after it are fused again from the new state. A
        row that fails again keeps its unloaded prediction, and the rows after
        it their first results. Costs one more kernel call over the rest of the
        log per row redone.

        ``buf`` is the batch's private copy of the filter's buffer, holding the
        kernel's result, and is updated in place; the caller puts it in place
        afterwards (interrupted part-way, the filter stays as before the log).
        """
        out_x, out_p, status, nis = outputs
        rows = buf.reshape(k.BUF_ROWS, k.W)
        x = rows[k.BUF_X]
        p = rows[k.BUF_P : k.BUF_P + 6]
        n = len(log)
        j = 0
        while True:
            bad = np.flatnonzero(status[j:] == NOT_POSITIVE_DEFINITE)
            if not bad.size:
                break
            j += int(bad[0])
            final = buf.copy()
            x[:] = out_x[j]
            p[:, :] = out_p[j]
            _load(buf)
            rows[k.BUF_MEAS, :4] = log.values[j]
            rows[k.BUF_MEAS + 1, :4] = variances[j]
            m = int(np.count_nonzero(variances[j] > 0.0))
            # Batch mode (count -1) with a time step of 0: the update alone.
            code, value = _step(buf, 0.0, 0, -1, 0.0, 0.0, 0.0, 0.0, float(self._gates[m]))
            if code == NOT_POSITIVE_DEFINITE:
                np.copyto(buf, final)
                j += 1
                continue
            out_x[j] = x
            out_p[j] = p
            status[j] = code
            nis[j] = value
            buf[BUF_TIME] = log.times[j]
            j += 1
            if j == n:
                break
            # planar_run undoes a TIME_GAP in its row 0 from its last output row.
            out_x[-1] = x
            out_p[-1] = p
            k.planar_run(
                buf, log.times[j:], log.values[j:], variances[j:], self._gates,
                out_x[j:], out_p[j:], status[j:], nis[j:], k.step_address(),
            )  # fmt: skip

    def __repr__(self) -> str:
        # A user subclass is named as itself (as navkit's potential fields are), with the
        # filter's own time and state: not its t and x, which it may override.
        t = PlanarFusion.t.__get__(self)
        x = PlanarFusion.x.__get__(self)
        # Each state as Python writes a float (as Pose2D's repr and the odometries'):
        # rounding to a few digits showed a UTM position 4.6123e+06 (to 50 m).
        state = ", ".join(repr(float(v)) for v in x)
        return f"{type(self).__name__}(t={t}, x=[{state}])"


def _loaded_into(buf: FloatArray, t: float, args: _StepArgs) -> tuple[int, float]:
    """Redo an online step that lost positive definiteness, from a loaded prediction.

    Called with the step undone. On a copy of ``buf``: the prediction to
    ``t`` alone, its variances raised by :data:`_LOADING` of themselves
    (:func:`_load`), then the update at ``t``. The copy becomes ``buf``
    unless that update lost positive definiteness too; its saved state is
    ``buf``'s from before the call, so that an interrupt from here on undoes
    the whole call (:meth:`PlanarFusion._settle`). Returns the second step's
    status and NIS.
    """
    trial = buf.copy()
    if math.isnan(trial[BUF_TIME]):  # no clock before the step: no prediction
        trial[BUF_TIME] = t
    _step(trial, t, 0, 0, 0.0, 0.0, 0.0, 0.0, math.inf)  # it did not overflow before
    _load(trial)
    status, nis = _step(trial, t, *args)
    if status == NOT_POSITIVE_DEFINITE:
        return status, nis
    # The saved block: x, P and the time from before the call, as after a plain step.
    trial[_SAVED] = buf[_STATE]
    trial[BUF_SAVED_TIME] = buf[BUF_TIME]
    np.copyto(buf, trial)  # one C call: Python delivers no interrupt inside it
    return status, nis


def _rejection(status: int, nis: float, residual: FloatArray) -> UpdateResult:
    """The result of a measurement gated or overflowing (``status``), the prediction kept."""
    if not np.all(np.isfinite(residual)):
        residual = np.empty(0)
    # Gated and overflowing measurements still advance the clock: the kernel kept
    # the prediction and set the time.
    if status == GATED:
        return rejected_result(
            nis, residual, f"rejected by the gate: NIS {nis:.6g}", FusionStatus.GATED
        )
    assert status == OVERFLOW
    return rejected_result(
        nis,
        residual,
        "overflow: the update would overflow float64 (the measurement is absurdly far "
        "from the state for its variance); the prediction is kept",
        FusionStatus.OVERFLOW,
    )


def _restore_fusion(
    buf: FloatArray,
    gates: FloatArray,
    cls: type[PlanarFusion] = PlanarFusion,
    anchor: tuple[float, float] = (0.0, 0.0),
    kept: tuple[float, Sequence[_Entry]] = (0.0, ()),
) -> PlanarFusion:
    """A :class:`PlanarFusion` (or ``cls``) with the given buffer, gates, anchor and history.

    For unpickling and copies; pickles made before ``cls`` existed pass two
    arguments, those made before the anchor (whose buffers hold the absolute
    position) three, and those made before ``history`` four.
    """
    fusion: PlanarFusion = object.__new__(cls)
    anchored_at = (float(anchor[0]), float(anchor[1]))
    fusion._adopt(buf, gates, anchored_at, float(kept[0]), list(kept[1]))
    return fusion


def _matrix(value: ArrayLike, name: str, *, semidefinite: bool) -> FloatArray:
    arr = as_float_array(value, name)
    if arr.shape == (6,):
        check_magnitude(arr, name)
        if not np.all(arr >= 0.0) or (not semidefinite and not np.all(arr > 0.0)):
            bound = ">= 0" if semidefinite else "> 0"
            raise ValueError(f"{name} diagonal entries must be {bound}")
        # The diagonal goes through the same checks as a full matrix: a positive but
        # subnormal variance (1e-320) passes the test above, yet the kernel's LDLᵀ
        # check refuses it, and the filter would fail its first update instead.
        arr = np.diag(arr)
    return covariance(arr, name, 6, semidefinite=semidefinite)


def _start_state(x0: ArrayLike | None, pose: Pose2D | ArrayLike | None) -> FloatArray:
    """The start state ``[x, y, θ, v, ω, a]`` from ``x0`` or ``pose``, checked.

    For :class:`PlanarFusion` and :meth:`PlanarFusion.reset`.
    """
    if pose is not None and x0 is not None:
        raise ValueError("give x0 or pose, not both (pose is x0 with zero rates)")
    if pose is not None:
        start = as_pose(pose, "pose")
        return np.array([start.x, start.y, start.theta, 0.0, 0.0, 0.0])
    if x0 is None:
        return np.zeros(6)
    # A start pose given as the first argument (review 53, PIPELINE): the way out
    # is the keyword the odometry classes and the simulator take it by.
    way_out = "; a start pose goes in as pose= (x0 with zero rates)"
    if isinstance(x0, Pose2D):
        raise TypeError(f"x0 must be the state [x, y, yaw, v, omega, a], got a Pose2D{way_out}")
    # components: a list holding a Pose2D got the advice for points, (p.x, p.y),
    # which x0 refuses in turn (review 53, FRESH3).
    state = as_float_array(x0, "x0", finite=False, components=6)
    if state.shape == (3,):
        raise ValueError(f"x0 must be the state [x, y, yaw, v, omega, a], got shape (3,){way_out}")
    return as_float_array(state, "x0", shape=(6,))


def _start_buffer(
    x: FloatArray,
    P0: ArrayLike | None,
    t0: float | None,
    *,
    process_noise: ArrayLike | None = None,
    q: FloatArray | None = None,
) -> tuple[FloatArray, tuple[float, float]]:
    """A filter's buffer at the start state ``x``, and the anchor its x and y are relative to.

    ``P0``, ``process_noise`` (unless ``q``, a filter's own checked process
    noise, is given) and ``t0`` are checked in that order, as the constructor
    documents them. For :class:`PlanarFusion` and :meth:`PlanarFusion.reset`:
    a reset filter's buffer is the one a new filter would have, bit for bit.
    """
    # x, P, Q, the current measurement, the filter time and scratch space live in one
    # flat array: the compiled online step takes just that array (see
    # _fusion_kernels.BUF_*).
    buf = np.zeros(k.BUF_SIZE)
    rows = buf.reshape(k.BUF_ROWS, k.W)
    # The buffer holds x and y less the start's (see _odometry.anchored): the motion summed
    # apart from the start, which far from the origin would round every step.
    ax = anchored(float(x[0]))
    ay = anchored(float(x[1]))
    state = rows[k.BUF_X]
    state[:] = x
    state[0] -= ax  # exactly 0.0, or x as given when not anchored
    state[1] -= ay
    state[2] = wrap_angle(float(state[2]))
    rows[k.BUF_P : k.BUF_P + 6] = _matrix(
        DEFAULT_INITIAL_VARIANCE if P0 is None else P0, "P0", semidefinite=False
    )
    if q is None:
        q = _matrix(
            DEFAULT_PROCESS_NOISE if process_noise is None else process_noise,
            "process_noise",
            semidefinite=True,
        )
    rows[k.BUF_Q : k.BUF_Q + 6] = q
    # NaN until the clock is set (by t0 or the first measurement).
    buf[BUF_TIME] = math.nan if t0 is None else as_time(t0, "t0")
    if t0 is not None:
        buf[_BUF_ORIGIN] = buf[BUF_TIME]
    return buf, (ax, ay)
