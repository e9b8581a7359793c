"""Outcome of a filter measurement update."""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from navkit._shared.frozen import frozen_setattr, reduce_record
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array

__all__ = ["UpdateResult"]


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class UpdateResult:
    """What happened to one measurement.

    Attributes
    ----------
    accepted : bool
        True when the measurement changed the state.
    nis : float
        Normalised innovation squared yᵀ S⁻¹ y (dimensionless; chi-square
        distributed with ``len(residual)`` degrees of freedom for a consistent
        filter). NaN when it was never computed (e.g. out-of-order measurement);
        inf when it overflowed float64 (the measurement is then not applied).
    residual : ndarray, shape (m,)
        Innovation y = z - h(x) with angle components wrapped to (-π, π]; empty
        when it was never computed or overflowed float64.
    reason : str or None
        Why the measurement was not applied; None when ``accepted``.

    Examples
    --------
    >>> r = UpdateResult(False, 30.2, np.array([5.0]), "rejected by the gate")
    >>> bool(r), r.reason
    (False, 'rejected by the gate')
    """

    accepted: bool
    nis: float
    residual: FloatArray
    reason: str | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.accepted, (bool, np.bool_)):
            raise TypeError(f"accepted must be a bool, got {type(self.accepted).__name__}")
        object.__setattr__(self, "accepted", bool(self.accepted))
        nis = as_float_array(self.nis, "nis", shape=(), finite=False)
        if float(nis) < 0.0:
            raise ValueError(f"nis must be >= 0 or NaN, got {float(nis)}")
        object.__setattr__(self, "nis", float(nis))
        residual = np.array(as_float_array(self.residual, "residual", ndim=1), copy=True)
        residual.flags.writeable = False
        object.__setattr__(self, "residual", residual)
        if self.reason is not None and not isinstance(self.reason, str):
            raise TypeError(f"reason must be a str or None, got {type(self.reason).__name__}")
        if self.accepted and self.reason is not None:
            raise ValueError(f"reason must be None when accepted, got {self.reason!r}")

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: ``residual`` read-only, also in subclasses' copies.

        Through :func:`~navkit._shared.frozen.reduce_record`, so that a subclass keeps
        its class, its own fields and attributes. A writeable residual (the one a
        filter returns) is held as a read-only view: the original keeps its own.
        """
        return reduce_record(self, ("residual",))

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle with a read-only ``residual``.

        An unpickled or deep-copied array is writeable again. A writeable one (also
        the residual a filter returns, shared by a :func:`copy.copy`) is replaced by
        a read-only copy, leaving the original result's array as it was.
        """
        for field, value in zip(fields(self), state, strict=True):
            object.__setattr__(self, field.name, value)
        residual = self.residual
        if isinstance(residual, np.ndarray) and residual.flags.writeable:
            residual = residual.copy()
            residual.flags.writeable = False
            object.__setattr__(self, "residual", residual)

    def __bool__(self) -> bool:
        return self.accepted


_object_new = object.__new__
_set_accepted = UpdateResult.__dict__["accepted"].__set__
_set_nis = UpdateResult.__dict__["nis"].__set__
_set_residual = UpdateResult.__dict__["residual"].__set__
_set_reason = UpdateResult.__dict__["reason"].__set__


def new_result(
    accepted: bool, nis: float, residual: FloatArray, reason: str | None
) -> UpdateResult:
    """Build an :class:`UpdateResult` without its validating constructor, for the filters.

    A frozen dataclass's ``__init__`` routes every field through
    ``object.__setattr__`` and ``__post_init__`` validates and copies the
    residual; the online filter builds one result per measurement (a few
    microseconds each), so it fills the slots directly instead. The caller
    guarantees valid fields and passes a ``residual`` it owns (a fresh copy
    nothing else references), which is therefore neither copied again nor made
    read-only (that flag alone costs about a tenth of an online filter step).
    """
    result: UpdateResult = _object_new(UpdateResult)
    _set_accepted(result, accepted)
    _set_nis(result, nis)
    _set_residual(result, residual)
    _set_reason(result, reason)
    return result
