"""Outcome of a filter measurement update."""

from __future__ import annotations

import numbers
from dataclasses import dataclass, fields
from typing import TYPE_CHECKING, Any

import numpy as np

from navkit._shared.frozen import frozen_setattr, reduce_record, restore_extra
from navkit._shared.text import as_text
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array, bounded_int, is_ndarray

if TYPE_CHECKING:
    from navkit.estimation._fusion import FusionStatus

__all__ = ["UpdateResult"]


def _fusion_status() -> type[FusionStatus]:
    """:class:`FusionStatus`, imported on use: its module imports this one."""
    from navkit.estimation._fusion import FusionStatus

    return FusionStatus


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
        Why the measurement was not applied, as a message; None when ``accepted``.
    status : FusionStatus or None
        The outcome as a code, the :class:`FusionStatus` that
        ``FusionResult.status`` holds for each row of a batch: ``ACCEPTED``
        exactly when ``accepted``; from the filters otherwise ``GATED``,
        ``OVERFLOW`` or (:class:`PlanarFusion`) ``OUT_OF_ORDER``. None for a
        rejected result built without one (the default).

    Raises
    ------
    TypeError
        ``accepted`` not a bool, ``nis`` or ``residual`` not real numbers,
        ``reason`` not a str or None, ``status`` not a FusionStatus code.
    ValueError
        ``nis`` negative (NaN is allowed), ``residual`` not one-dimensional or
        not finite, a ``reason`` for an accepted update, ``status`` an
        unknown code or one that contradicts ``accepted``.

    Examples
    --------
    >>> from navkit.estimation import FusionStatus
    >>> r = UpdateResult(False, 30.2, np.array([5.0]), "rejected by the gate",
    ...                  FusionStatus.GATED)
    >>> bool(r), r.reason, r.status is FusionStatus.GATED
    (False, 'rejected by the gate', True)
    >>> UpdateResult(True, 0.5, np.array([0.1])).status is FusionStatus.ACCEPTED
    True
    """

    accepted: bool
    nis: float
    residual: FloatArray
    reason: str | None = None
    status: FusionStatus | None = None

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
        if self.reason is not None:
            if not isinstance(self.reason, str):
                raise TypeError(f"reason must be a str or None, got {type(self.reason).__name__}")
            # Plain str: an np.str_ printed as np.str_('...') in the record's repr.
            object.__setattr__(self, "reason", as_text(self.reason, "reason"))
        if self.accepted and self.reason is not None:
            raise ValueError(f"reason must be None when accepted, got {self.reason!r}")
        codes = _fusion_status()
        raw: object = self.status  # as passed: any object
        status: FusionStatus | None
        if raw is None:
            status = codes.ACCEPTED if self.accepted else None
        elif isinstance(raw, codes):
            status = raw
        elif is_ndarray(raw) and raw.ndim == 0 and raw.dtype.kind in "iu":
            # A 0-d integer array is its integer; a masked one is refused as FusionStatus
            # refuses it (ValueError), naming this argument.
            code = bounded_int(raw, "status")
            try:
                status = codes(code)
            except ValueError:
                raise ValueError(f"status must be a FusionStatus code, got {raw!r}") from None
        elif isinstance(raw, (bool, np.bool_)) or not isinstance(raw, numbers.Integral):
            raise TypeError(f"status must be a FusionStatus or None, got {type(raw).__name__}")
        else:
            try:
                status = codes(int(raw))
            except ValueError:
                raise ValueError(f"status must be a FusionStatus code, got {raw!r}") from None
        if status is not None and (status is codes.ACCEPTED) != self.accepted:
            raise ValueError(
                f"status must be ACCEPTED exactly when accepted, got {status.name} with "
                f"accepted={self.accepted}"
            )
        object.__setattr__(self, "status", status)

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: ``residual`` read-only, also in subclasses' copies.

        Through :func:`~navkit._shared.frozen.reduce_record`, so that a subclass keeps
        its class, its own fields and attributes. A writeable residual (the one a
        filter returns) is held as a read-only view: the original keeps its own.
        """
        return reduce_record(self, ("residual",))

    def __setstate__(self, state: list[Any] | tuple[Any, Any]) -> None:
        """Restore from an older pickle with a read-only ``residual``.

        An unpickled or deep-copied array is writeable again. A writeable one (also
        the residual a filter returns, shared by a :func:`copy.copy`) is replaced by
        a read-only copy, leaving the original result's array as it was. A
        pickle from before ``status`` existed leaves it unset (see ``_Status``).
        A tuple is what a subclass adds, restored after the rebuild
        (:func:`~navkit._shared.frozen.reduce_record`).
        """
        if isinstance(state, tuple):
            restore_extra(self, state)
            return
        for field, value in zip(fields(self), state, strict=False):
            object.__setattr__(self, field.name, value)
        residual = self.residual
        if isinstance(residual, np.ndarray) and residual.flags.writeable:
            residual = residual.copy()
            residual.flags.writeable = False
            object.__setattr__(self, "residual", residual)

    def __bool__(self) -> bool:
        return self.accepted


class _Status:
    """``UpdateResult.status`` over its slot: an unset slot reads from ``accepted``.

    The filters' per-measurement paths build results slot by slot and leave
    ``status`` unset when accepted (one store fewer per update): it then reads
    as ``ACCEPTED`` (None for a rejected result unpickled from before the field).
    """

    __slots__ = ("_slot",)

    def __init__(self, slot: Any) -> None:
        self._slot = slot

    def __get__(self, result: UpdateResult | None, owner: type | None = None) -> Any:
        if result is None:
            return self
        try:
            return self._slot.__get__(result, owner)
        except AttributeError:
            return _fusion_status().ACCEPTED if result.accepted else None

    def __set__(self, result: UpdateResult, value: Any) -> None:
        self._slot.__set__(result, value)

    def __delete__(self, result: UpdateResult) -> None:
        self._slot.__delete__(result)


_status_slot = UpdateResult.__dict__["status"]
type.__setattr__(UpdateResult, "status", _Status(_status_slot))

_set_status = _status_slot.__set__


class _Building:
    """An :class:`UpdateResult` under construction: its slots, with plain stores.

    The filters build one result per measurement. A frozen dataclass's fields
    can be set only through their slot descriptors (four method-wrapper calls,
    about 40 ns each, a fifth of an online step); an instance of this class,
    whose slots are laid out as UpdateResult's (the same names in the same
    order), takes plain attribute stores and then becomes an UpdateResult by
    assigning ``__class__``, which Python allows between classes of one layout.
    The result is an UpdateResult like any other; building it costs about half.
    (A free-threaded CPython stops the world for such an assignment; numba, and
    so navkit, runs on builds with the GIL.)
    """

    __slots__ = UpdateResult.__slots__
    accepted: bool
    nis: float
    residual: FloatArray
    reason: str | None
    status: FusionStatus


def new_result(
    accepted: bool, nis: float, residual: FloatArray, reason: str | None
) -> UpdateResult:
    """Build an :class:`UpdateResult` without its validating constructor, for the filters.

    A frozen dataclass's ``__init__`` routes every field through
    ``object.__setattr__`` and ``__post_init__`` validates and copies the
    residual; the online filters build one result per measurement (a few
    microseconds each), so they fill the slots directly instead (see
    :class:`_Building`, which hot paths use written out). The caller
    guarantees valid fields and passes a ``residual`` it owns (a fresh copy
    nothing else references), which is therefore neither copied again nor made
    read-only (that flag alone costs about a tenth of an online filter step).
    ``status`` is left unset: it reads as ``ACCEPTED`` when ``accepted``.
    """
    result = _Building()
    result.accepted = accepted
    result.nis = nis
    result.residual = residual
    result.reason = reason
    result.__class__ = UpdateResult  # type: ignore[assignment]
    return result  # type: ignore[return-value]


def rejected_result(
    nis: float, residual: FloatArray, reason: str, status: FusionStatus
) -> UpdateResult:
    """A not-applied :class:`UpdateResult` for the filters, with its ``status``.

    As :func:`new_result` (no validation or copy); ``status`` is not ``ACCEPTED``.
    """
    result = new_result(False, nis, residual, reason)
    _set_status(result, status)
    return result
