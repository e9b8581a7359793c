"""Range noise of a simulated LiDAR, by distance band."""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from navkit._shared.deprecation import positional_deprecated
from navkit._shared.frozen import frozen_setattr, restore_read_only
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array, finite_float, unpack

__all__ = ["RangeNoise"]

#: The omnidirectional robot paper's RPLIDAR measurements: relative range error
#: 2.23 % at short range and 5.38 % at long range. The paper gives no boundary
#: between the two; navkit uses 3 m, where the RPLIDAR A1 datasheet's accuracy
#: class changes.
PAPER_LIMITS = (3.0, math.inf)
PAPER_SIGMA = (0.0223, 0.0538)


def _floats(
    value: Sequence[float] | NDArray[np.generic], name: str, *, allow_inf: bool = False
) -> tuple[float, ...]:
    """``value`` as a tuple of finite floats (``+inf`` too with ``allow_inf``)."""
    if isinstance(value, (str, bytes, Mapping)):
        raise TypeError(f"{name} must be a sequence of numbers, got {type(value).__name__}")
    if isinstance(value, np.ndarray):
        # Dtype and dimension checked as for any array argument: an empty array of
        # strings or booleans has no element for the checks below to refuse.
        value = as_float_array(value, name, ndim=1, finite=False)
    try:
        items = unpack(value, name)
    except TypeError:
        kind = type(value).__name__
        raise TypeError(f"{name} must be a sequence of numbers, got {kind}") from None
    out = []
    for i, item in enumerate(items):
        if allow_inf and isinstance(item, (float, np.floating)) and item == math.inf:
            out.append(math.inf)
        else:
            out.append(finite_float(item, f"{name}[{i}]"))
    return tuple(out)


def _no_absolute_term(noise: Any) -> tuple[float, ...]:
    """``absolute`` of a :class:`RangeNoise` made before it existed: zeros, one a band."""
    return (0.0,) * len(noise.sigma)


# Keyword-only as every sensor configuration: sigma and bias are both tuples of
# small floats, and swapped by position they passed validation.
@positional_deprecated
@frozen_setattr
@dataclass(frozen=True, slots=True, kw_only=True)
class RangeNoise:
    """Gaussian range error of a LiDAR, by distance band: relative, plus absolute.

    A reading of true range ``r`` in band ``b`` (the first band with
    ``r < limits[b]``) is ``r * (1 + bias[b] + sigma[b] * z) + absolute[b] * z``
    with ``z`` standard normal (one draw a beam): ``sigma`` is the relative
    standard deviation (the "percentage error" of a datasheet), ``absolute``
    an absolute one in metres (a datasheet's "±15 mm" at short range), so the
    band's standard deviation is ``sigma[b] * r + absolute[b]``, and ``bias`` a
    relative mean error. Datasheets give each band one of the two kinds (the
    LDS-01: ±15 mm below 0.5 m, ±5 % beyond: ``limits=(0.5, inf),
    sigma=(0.0, 0.05), absolute=(0.015, 0.0)``). The default bands are the
    omnidirectional robot paper's RPLIDAR measurements: 2.23 % below 3 m and
    5.38 % beyond (the paper gives no boundary; 3 m is where the RPLIDAR A1
    datasheet's accuracy class changes), with no absolute term.

    Sizes share the one draw ``z``: with ``absolute`` 0 (the default) every
    reading is the relative model's to the bit, and changing only a size
    (``sigma`` or ``absolute`` of a noise that is on) keeps every draw of a
    seeded run.

    All four are keyword-only (by position ``limits``, ``sigma`` and ``bias``
    still work, with a ``DeprecationWarning``: ``sigma`` and ``bias`` are
    easily swapped).

    Parameters
    ----------
    limits : sequence of float, default (3.0, inf)
        Upper edge of each band, m: strictly increasing, in (0, 1e6], the last
        one ``inf``.
    sigma : sequence of float, default (0.0223, 0.0538)
        Relative standard deviation of each band, in [0, 1].
    bias : sequence of float, optional
        Relative mean error of each band, in [-0.5, 0.5]; zeros by default.
    absolute : sequence of float, optional
        Absolute standard deviation of each band, m, in [0, 1000]; zeros by
        default (review 49).

    Raises
    ------
    TypeError
        ``limits``, ``sigma``, ``bias`` or ``absolute`` not a sequence of numbers.
    ValueError
        Values outside their ranges, NaN, or sequences of different lengths.

    Examples
    --------
    >>> RangeNoise()
    RangeNoise(limits=(3.0, inf), sigma=(0.0223, 0.0538), bias=(0.0, 0.0), absolute=(0.0, 0.0))
    >>> RangeNoise(limits=(1.0, float("inf")), sigma=(0.01, 0.02), bias=(0.0, 0.005)).sigma
    (0.01, 0.02)
    >>> lds01 = RangeNoise(limits=(0.5, math.inf), sigma=(0.0, 0.05), absolute=(0.015, 0.0))
    >>> lds01.absolute
    (0.015, 0.0)
    """

    limits: tuple[float, ...] = PAPER_LIMITS
    sigma: tuple[float, ...] = PAPER_SIGMA
    bias: tuple[float, ...] = field(default=())
    # Added in review 49: never positional, as it never was.
    absolute: tuple[float, ...] = field(default=(), metadata={"positional": False})

    # Fields added since a release, for pickles made before (see
    # navkit._shared.frozen.fill_added_fields): no absolute term then. Not annotated:
    # it would be a field.
    _added_fields = MappingProxyType({"absolute": _no_absolute_term})

    if TYPE_CHECKING:
        # The generated ``__init__`` takes any sequence of numbers or a 1-D array
        # (``__post_init__`` makes tuples of them); this signature tells type checkers so.
        def __init__(
            self,
            *,
            limits: Sequence[float] | NDArray[np.generic] = ...,
            sigma: Sequence[float] | NDArray[np.generic] = ...,
            bias: Sequence[float] | NDArray[np.generic] = ...,
            absolute: Sequence[float] | NDArray[np.generic] = ...,
        ) -> None: ...

    def __post_init__(self) -> None:
        limits = _floats(self.limits, "limits", allow_inf=True)
        sigma = _floats(self.sigma, "sigma")
        bias = _floats(self.bias, "bias") or (0.0,) * len(sigma)
        absolute = _floats(self.absolute, "absolute") or (0.0,) * len(sigma)
        n = len(limits)
        if n == 0:
            raise ValueError("limits must hold at least one band")
        if len(sigma) != n or len(bias) != n or len(absolute) != n:
            raise ValueError(
                f"limits, sigma, bias and absolute must have one entry per band, got {n}, "
                f"{len(sigma)}, {len(bias)} and {len(absolute)}"
            )
        if limits[-1] != math.inf:
            raise ValueError(f"the last limit must be inf (the open last band), got {limits[-1]}")
        for i, lim in enumerate(limits[:-1]):
            if not 0.0 < lim <= 1e6:
                raise ValueError(f"limits[{i}] must lie in (0, 1e6] m, got {lim}")
        if any(b <= a for a, b in itertools.pairwise(limits)):
            raise ValueError(f"limits must be strictly increasing, got {limits}")
        for i, s in enumerate(sigma):
            if not 0.0 <= s <= 1.0:
                raise ValueError(f"sigma[{i}] must lie in [0, 1] (relative), got {s}")
        for i, b in enumerate(bias):
            if not -0.5 <= b <= 0.5:
                raise ValueError(f"bias[{i}] must lie in [-0.5, 0.5] (relative), got {b}")
        for i, a in enumerate(absolute):
            if not 0.0 <= a <= 1000.0:
                raise ValueError(f"absolute[{i}] must lie in [0, 1000] m, got {a}")
        object.__setattr__(self, "limits", limits)
        object.__setattr__(self, "sigma", sigma)
        object.__setattr__(self, "bias", bias)
        object.__setattr__(self, "absolute", absolute)

    def __setstate__(self, state: Sequence[Any]) -> None:
        """Restore from a pickle or copy (and what a subclass adds, see ``restore_read_only``).

        A pickle made before review 49 holds the first three fields only: a noise
        without an absolute term, ``absolute`` zeros as its default (``_added_fields``;
        a subclass's pickle of then too, review 50).
        """
        restore_read_only(self, state, ())

    def arrays(self) -> tuple[FloatArray, FloatArray, FloatArray]:
        """``(limits, bias, sigma)`` as new float64 arrays, for the noise kernel.

        Returns
        -------
        limits, bias, sigma : ndarray, shape (B,)
            One entry per band: upper edges (m, the last ``inf``), relative
            mean errors and relative standard deviations.

        Examples
        --------
        >>> noise = RangeNoise(limits=(1.0, math.inf), sigma=(0.01, 0.02), bias=(0.0, 0.005))
        >>> limits, bias, sigma = noise.arrays()
        >>> limits.tolist(), bias.tolist(), sigma.tolist()
        ([1.0, inf], [0.0, 0.005], [0.01, 0.02])
        >>> sigma[0] = 0.5  # a new array: the noise itself is unchanged
        >>> noise.sigma
        (0.01, 0.02)
        """
        return (
            np.array(self.limits, dtype=np.float64),
            np.array(self.bias, dtype=np.float64),
            np.array(self.sigma, dtype=np.float64),
        )
