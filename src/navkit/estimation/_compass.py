"""Compass readings (degrees clockwise from north) to robot yaw (radians, counter-clockwise)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from types import MappingProxyType
from typing import Any, overload

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.dunders import slot_state
from navkit._shared.frozen import restore_slots
from navkit._shared.types import FloatArray, RealScalar
from navkit._shared.validation import as_bool, as_float_array, finite_float

__all__ = ["CompassCalibration", "compass_to_yaw"]


@overload
def compass_to_yaw(
    raw_deg: RealScalar, *, initial_deg: float = ..., unwrap: bool = ...
) -> float: ...
@overload
def compass_to_yaw(
    raw_deg: Sequence[float] | Sequence[Sequence[float]],
    *,
    initial_deg: float = ...,
    unwrap: bool = ...,
) -> FloatArray: ...
@overload
def compass_to_yaw(
    raw_deg: ArrayLike, *, initial_deg: float = ..., unwrap: bool = ...
) -> float | FloatArray: ...


def compass_to_yaw(
    raw_deg: ArrayLike, *, initial_deg: float = 0.0, unwrap: bool = False
) -> float | FloatArray:
    r"""Convert compass headings to a yaw relative to the initial heading.

    A compass reads 0–360° clockwise from magnetic north; robot yaw is
    counter-clockwise positive. Following the omnidirectional-robot paper: the
    relative heading :math:`\theta_r = (\theta - \theta_0 + 360) \bmod 360`, then
    the signed yaw is :math:`-\theta_r` for :math:`\theta_r < 180` and
    :math:`360 - \theta_r` otherwise, returned in radians in (-π, π] (180° maps
    to +π).

    Parameters
    ----------
    raw_deg : float or array_like
        Compass heading(s), degrees clockwise from north (any finite value; it is
        taken modulo 360).
    initial_deg : float, default 0.0
        Heading θ0 (degrees) that defines yaw 0, usually the first reading
        (keyword-only).
    unwrap : bool, default False
        For a 1-D log: return a continuous yaw (no 2π jumps, as
        :func:`numpy.unwrap`), starting from the wrapped first value
        (keyword-only; a ``bool``). A step between successive wrapped yaws
        larger than π in magnitude is replaced by the one 2π shorter; a step
        of exactly ±π (readings 180° apart) is kept as it is, so a jump there
        and back returns to the start: ``[0, 180, 0]`` degrees give
        ``[0, π, 0]``. :class:`CompassCalibration` follows the same rule.
        The turns are counted as integers, the yaw the wrapped one plus 2π
        times their count: within 1.61 ulps of the exact value after any
        number of turns (its float spacing is 1e-9 rad at 10^6
        turns), where :func:`numpy.unwrap`'s running float sum of its
        corrections drifts (7,675 ulps, 9e-7 rad, after 111,111 turns), so the
        two differ in the last bits; wrap it
        (:func:`navkit.geometry.wrap_angle`) for a heading.

    Returns
    -------
    float or ndarray
        Yaw in radians: a float for scalar input, otherwise a new array of the
        input's shape.

    Raises
    ------
    TypeError
        ``raw_deg`` or ``initial_deg`` not real numbers, ``unwrap`` not a bool.
    ValueError
        Non-finite readings, or ``unwrap`` with readings that are not 1-D.

    Examples
    --------
    >>> compass_to_yaw(90.0)  # a quarter turn clockwise
    -1.5707963267948966
    >>> compass_to_yaw([10.0, 350.0], initial_deg=20.0).round(4)
    array([0.1745, 0.5236])
    >>> compass_to_yaw([170.0, 190.0, 210.0], unwrap=True).round(4)
    array([-2.9671, -3.3161, -3.6652])
    >>> compass_to_yaw([0.0, 180.0, 0.0], unwrap=True).round(4)
    array([0.    , 3.1416, 0.    ])
    """
    raw = as_float_array(raw_deg, "raw_deg")
    theta0 = finite_float(initial_deg, "initial_deg")
    flag = as_bool(unwrap, "unwrap")
    # Reduce each angle first: raw - theta0 would round away the smaller of the two
    # once the other is large (1e20 - 10 == 1e20), or overflow. Each reduced angle
    # lies in [0, 360] (360 itself for a tiny negative angle: -1e-20 % 360 rounds up
    # to it), so diff lies in [0, 720] (never -0.0: -360 + 360 is +0.0), and the
    # remainder of a non-negative diff is exact: rel is in [0, 360), never 360.
    # (Were it 360, the yaw below would be 360 - 360 = +0.0, as for rel = 0.)
    diff = np.mod(raw, 360.0) - (theta0 % 360.0) + 360.0
    rel = np.mod(diff, 360.0)
    # 0.0 - rel, not -rel: a reading equal to the initial heading is yaw +0.0, not -0.0.
    yaw = np.radians(np.where(rel < 180.0, 0.0 - rel, 360.0 - rel))
    if flag:
        if yaw.ndim != 1:
            raise ValueError(f"unwrap needs a 1-D array of readings, got shape {yaw.shape}")
        yaw, _ = _unwrap_after(yaw, float(yaw[0]) if yaw.size else 0.0, 0.0)
    if yaw.ndim == 0:
        return float(yaw)
    out: FloatArray = np.asarray(yaw, dtype=np.float64)
    return out


#: 2π as a float: a yaw unwrapped by k turns is the wrapped one plus k * _TURN.
_TURN = 2.0 * math.pi


def _unwrap_after(yaw: FloatArray, previous: float, correction: float) -> tuple[FloatArray, float]:
    """Unwrap the 1-D wrapped ``yaw`` that follows the wrapped yaw ``previous``.

    ``correction`` is the multiple of 2π already added to ``previous`` (k ``_TURN``,
    k an integer; a float summed from rounded corrections, as a pickle made
    before review 53 holds, is taken as the nearest whole number of turns). The rule
    is :func:`numpy.unwrap`'s (a step of exactly ±π keeps its sign); the turns are
    counted as integers, so a log unwrapped in pieces, each continuing from the
    last, equals the whole log unwrapped at once, bit for bit. Returns the
    unwrapped yaw and the correction added to its last value.
    """
    step = np.diff(yaw, prepend=previous)
    reduced = np.mod(step + np.pi, 2.0 * np.pi) - np.pi
    # np.mod puts a step of +π at -π; numpy.unwrap gives it back its sign.
    reduced = np.where((reduced == -np.pi) & (step > 0.0), np.pi, reduced)
    # Whole turns, counted as integers (a step between wrapped yaws is within 2π, so
    # each is -1, 0 or 1), the yaw rounded once from them: numpy.unwrap's running sum
    # of its rounded corrections drifted 7,675 ulps (9e-7 rad) off the exact yaw
    # after 111,111 turns (2.6 after one), this stays within 1.61 ulps: half an ulp of
    # k·2π's rounding (a whole ulp of the yaw where k·2π is past a power of two the
    # yaw is not), half of the sum's, and k times 2π's own error, 2.45e-16 (at most
    # 0.36 ulp); 1.6033 is reached at k = -41, yaw -256 + 4.8e-6 (review 53, FOUND6;
    # the bound corrected from 1.35 by FRESH3).
    turns = np.where(np.abs(step) < np.pi, 0.0, np.rint((reduced - step) / _TURN))
    total = np.cumsum(np.concatenate(([round(correction / _TURN)], turns)))[1:] * _TURN
    out: FloatArray = yaw + total
    return out, float(total[-1]) if total.size else correction


class CompassCalibration:
    """Stateful compass-to-yaw conversion that latches the first reading as θ0.

    The first reading given to :meth:`__call__` (the first element of an array)
    becomes the initial heading; every reading is then converted with
    :func:`compass_to_yaw`. With ``unwrap=True`` the yaw is continuous across
    calls (successive readings never jump by 2π), as needed for logs that are
    streamed in pieces.

    The first reading's noise stays in every yaw as a constant offset: with
    readings of independent noise of standard deviation σ, each yaw (after
    the first, which is exactly 0) is off by the difference of two readings'
    noise, standard deviation σ√2, and any two yaws' errors are correlated
    by 1/2 (the first reading's share). Where that matters (a filter fusing
    the yaws as independent readings of variance σ² would be overconfident),
    latch a heading averaged over readings taken standing still instead:
    :func:`compass_to_yaw` with that ``initial_deg``.

    An ordinary class with ``__slots__`` rather than a frozen dataclass: it
    latches its first reading (and the last yaw when unwrapping). So it is not
    thread-safe: one thread at a time may call it; different calibrations may
    run in different threads at once.

    Parameters
    ----------
    unwrap : bool, default False
        Return a continuous yaw instead of one wrapped to (-π, π] (keyword-only;
        a ``bool``). The rule is :func:`compass_to_yaw`'s (that of
        :func:`numpy.unwrap`: a step of exactly ±π keeps its sign, so readings
        0°, 180°, 0° give yaw 0, π, 0); the yaws of a log given in pieces equal
        ``compass_to_yaw(log, initial_deg=log[0], unwrap=True)`` bit for bit,
        within 1.61 ulps of the exact yaw after any number of turns.

    Raises
    ------
    TypeError
        ``unwrap`` that is not a ``bool``.

    Examples
    --------
    >>> cal = CompassCalibration()
    >>> cal(45.0), cal.initial_deg
    (0.0, 45.0)
    >>> round(cal(135.0), 6)  # 90° clockwise of the start
    -1.570796
    >>> cal = CompassCalibration(unwrap=True)
    >>> [round(cal(d), 4) for d in (0.0, 170.0, 190.0)]
    [0.0, -2.9671, -3.3161]
    """

    __slots__ = ("__weakref__", "_correction", "_initial", "_last", "_unwrap")
    __getstate__ = slot_state  # pickle protocols 0 and 1 too
    # Slots added after a release (navkit._shared.frozen.fill_added_fields). Before
    # _correction (db2738d) _last held the last yaw unwrapped, not wrapped: unwrapping
    # the next readings from it with no correction gives them as that release did (the
    # first lands within π of it), and the state is today's from the next call on.
    _added_fields = MappingProxyType({"_correction": lambda calibration: 0.0})

    def __setstate__(self, state: Any) -> None:
        """Restore from a pickle, also one made before the unwrapping's correction."""
        restore_slots(self, state)

    def __init__(self, *, unwrap: bool = False) -> None:
        self._unwrap = as_bool(unwrap, "unwrap")
        self._initial: float | None = None
        # When unwrapping: the last wrapped yaw, and the multiple of 2π added to it.
        self._last: float | None = None
        self._correction = 0.0

    @property
    def initial_deg(self) -> float | None:
        """Latched initial heading θ0 in degrees, or None before the first reading."""
        return self._initial

    def reset(self) -> None:
        """Forget θ0 (and the unwrapping history); the next reading is latched again.

        Examples
        --------
        >>> cal = CompassCalibration()
        >>> cal(45.0), cal.initial_deg
        (0.0, 45.0)
        >>> cal.reset()
        >>> cal.initial_deg is None
        True
        >>> cal(90.0), cal.initial_deg  # 90° is the new yaw 0
        (0.0, 90.0)
        """
        self._initial = None
        self._last = None
        self._correction = 0.0

    @overload
    def __call__(self, raw_deg: RealScalar) -> float: ...
    @overload
    def __call__(self, raw_deg: Sequence[float] | Sequence[Sequence[float]]) -> FloatArray: ...
    @overload
    def __call__(self, raw_deg: ArrayLike) -> float | FloatArray: ...

    def __call__(self, raw_deg: ArrayLike) -> float | FloatArray:
        """Yaw (rad) of compass reading(s) ``raw_deg`` (degrees clockwise from north).

        Returns a float for a scalar, otherwise a new array (1-D for
        ``unwrap=True``). Raises TypeError or ValueError, naming ``raw_deg``, for
        readings that are not finite real numbers, or not a scalar or 1-D with
        ``unwrap=True`` (as :func:`compass_to_yaw`); nothing is latched then.
        """
        raw = as_float_array(raw_deg, "raw_deg")
        if self._unwrap and raw.ndim > 1:
            # A log has one time axis: which way would a 2-D array be unwrapped?
            raise ValueError(
                f"unwrap needs a scalar or a 1-D array of readings (raw_deg), got shape {raw.shape}"
            )
        if raw.size == 0:
            return np.empty(raw.shape)
        if self._initial is None:
            self._initial = float(raw.flat[0])
        yaw = np.asarray(compass_to_yaw(raw, initial_deg=self._initial))
        if self._unwrap:
            flat = yaw.reshape(-1)
            previous = float(flat[0]) if self._last is None else self._last
            unwrapped, correction = _unwrap_after(flat, previous, self._correction)
            last = float(flat[-1])
            # Stored together, with no call between (Python delivers a
            # KeyboardInterrupt at calls): a correction without its last yaw would
            # unwrap the next readings from the wrong one, 2π off.
            self._correction = correction
            self._last = last
            yaw = unwrapped.reshape(yaw.shape)
        if yaw.ndim == 0:
            return float(yaw)
        return yaw

    def __repr__(self) -> str:
        # The latched reading is no argument: <...>, as for the other reprs in call form.
        start = "no reading yet" if self._initial is None else f"initial {self._initial} deg"
        return f"{type(self).__name__}(unwrap={self._unwrap}, <{start}>)"
