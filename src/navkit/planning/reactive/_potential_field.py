"""The potential-field base class, sums of fields, and helpers shared by the fields.

Every field maps world points ``(x, y)`` (m) to a scalar potential and to the
force ``-∇U``, both vectorised over ``(N, 2)`` point arrays with analytic
gradients. Fields add: ``field_a + field_b`` is a :class:`CompositeField` whose
potential and force are the sums of its parts (``sum(fields)`` works too; typed
code gives it a field to start from, ``sum(fields, CompositeField([]))``, as type
checkers type the default start, 0, as a possible result).
"""

from __future__ import annotations

import dataclasses
import functools
from abc import ABC, abstractmethod
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.frozen import frozen_setattr, reduce_record, restore_read_only
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array
from navkit.planning.reactive._limits import point, points

__all__ = ["CompositeField", "PotentialField"]


class PotentialField(ABC):
    """Base class of navkit's potential fields.

    The concrete fields are frozen slotted dataclasses: their arrays are read-only
    copies of the caller's input, so changing an array after building a field
    does not change the field, and assigning an attribute raises
    :class:`dataclasses.FrozenInstanceError`. Subclasses implement ``_potential``
    and ``_force`` on a validated ``(N, 2)`` float64 array; the public
    :meth:`potential` and :meth:`force` validate once.

    A field of your own is such a subclass (an :class:`AttractiveField` one can
    drive :class:`~navkit.control.PotentialFieldController`): ``_potential(pts)``
    returns shape ``(N,)``, ``_force(pts)`` shape ``(N, 2)``, world frame. For a
    class defined outside navkit both are checked wherever they are called (in
    a :class:`CompositeField`, :func:`sample_field` and the controller too):
    ``pts`` is a read-only view (the caller's points are never changed), and
    an output of another shape, a NaN or -inf potential or a non-finite force raises
    ``ValueError`` (``TypeError`` for a non-numeric one) naming the method; the
    result is the caller's own copy.

    Ranges (checked where a field is built and on every query): points within
    ``±1e9`` m in x and y, gains in ``[1e-12, 1e12]``, lengths (semi-axes,
    widths, radii, spreads) in ``[1e-6, 1e6]`` m (offset radii in ``[0, 1e6]``). Inside
    them potentials and forces are finite, except the documented ``+inf``
    potential of :class:`KhatibRepulsion` on an obstacle point.

    Examples
    --------
    >>> from navkit.planning import CompositeField, ConicAttraction, KhatibRepulsion
    >>> fields = [ConicAttraction((1.0, 0.0)),
    ...           KhatibRepulsion([[0.5, 0.5]], influence_radius=0.5)]
    >>> # An empty CompositeField as the start: type checkers type a bare sum as maybe 0.
    >>> total = sum(fields, CompositeField([]))  # the obstacle (0.71 m) is beyond reach
    >>> total.force([0.0, 0.0]), total.potential([0.0, 0.0])
    (array([[1., 0.]]), array([1.]))

    A field of your own, a uniform pull along +x of 0.5 (potential ``-0.5 x``):

    >>> import numpy as np
    >>> from dataclasses import dataclass
    >>> from numpy.typing import NDArray
    >>> @dataclass(frozen=True, slots=True, eq=False)
    ... class Wind(PotentialField):
    ...     strength: float = 0.5
    ...     def _potential(self, pts: NDArray[np.float64]) -> NDArray[np.float64]:
    ...         return -self.strength * pts[:, 0]
    ...     def _force(self, pts: NDArray[np.float64]) -> NDArray[np.float64]:
    ...         return np.tile([self.strength, 0.0], (len(pts), 1))
    >>> (Wind() + ConicAttraction((1.0, 0.0))).force([[0.0, 0.0], [2.0, 0.0]])
    array([[ 1.5,  0. ],
           [-0.5,  0. ]])
    """

    __slots__ = ()

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        for name in ("_potential", "_force"):
            # The one the instances call, wherever the MRO finds it: a mixin's (class
            # Mine(Mixin, ConicAttraction)) is a user's too, not only one in the body.
            owner = next(k for k in cls.__mro__ if name in k.__dict__)
            # Only a user's: navkit's own meet the contract and pay nothing for it.
            if owner.__module__ == "navkit" or owner.__module__.startswith("navkit."):
                continue
            attr = owner.__dict__[name]
            if (
                (callable(attr) or hasattr(type(attr), "__get__"))
                and not getattr(attr, "__isabstractmethod__", False)
                and not getattr(attr, "_navkit_checked", False)  # the dataclass's slots copy
            ):
                setattr(cls, name, _checked_output(attr, name))

    def __reduce__(self) -> tuple[Any, ...]:
        # Every field (a frozen slotted dataclass) copies and pickles as itself,
        # subclasses whole, read-only arrays read-only.
        if not hasattr(type(self), "__dataclass_fields__"):
            # A user's field that is no dataclass: as Python pickles any object (its
            # __dict__ and slots), where reduce_record raised a TypeError naming nothing.
            # Through its own __getstate__ if it has one (dropping a lock, say): its
            # __setstate__ reads that state.
            return _new_field, (type(self),), self.__getstate__()
        return reduce_record(self)

    def potential(self, points_xy: ArrayLike) -> FloatArray:
        """Potential energy at world points.

        Parameters
        ----------
        points_xy : array_like, shape (N, 2) or (2,)
            ``(x, y)`` positions in metres, ``|x|, |y| <= 1e9``; a single point
            gives ``N = 1``, an empty input ``N = 0``.

        Returns
        -------
        ndarray, shape (N,)
            The potential ``U`` at each point (``+inf`` on a Khatib obstacle),
            in the units the field's gains give it (a gain times its distance
            law of metres).

        Raises
        ------
        ValueError
            Bad shape, NaN, infinities or coordinates beyond ±1e9 m.
        TypeError
            Non-numeric points (strings, complex numbers, booleans).

        Examples
        --------
        >>> from navkit.planning import ConicAttraction, KhatibRepulsion
        >>> ConicAttraction((3.0, 4.0)).potential([[0.0, 0.0], [3.0, 4.0]])  # U = d
        array([5., 0.])

        Khatib's ``U = k_rep (1/d - 1/d0)² / 2``: infinite on the obstacle,
        0.5 at half the influence radius, zero beyond it:

        >>> field = KhatibRepulsion([[1.0, 0.0]], k_rep=1.0, influence_radius=1.0)
        >>> field.potential([[1.0, 0.0], [0.5, 0.0], [3.0, 0.0]])
        array([inf, 0.5, 0. ])
        """
        pts = points(points_xy, "points_xy")
        try:
            return self._potential(pts)
        except FloatingPointError:
            return _redone(self._potential, pts)

    def force(self, points_xy: ArrayLike) -> FloatArray:
        """Force ``-∇U`` at world points.

        Parameters
        ----------
        points_xy : array_like, shape (N, 2) or (2,)
            ``(x, y)`` positions in metres, ``|x|, |y| <= 1e9``; a single point
            gives ``N = 1``, an empty input ``N = 0``.

        Returns
        -------
        ndarray, shape (N, 2)
            The force ``(Fx, Fy)`` at each point, in the world frame (the
            potential's units per metre;
            :class:`~navkit.control.PotentialFieldController` reads it as a
            velocity in m/s); always finite.

        Raises
        ------
        ValueError
            Bad shape, NaN, infinities or coordinates beyond ±1e9 m.
        TypeError
            Non-numeric points (strings, complex numbers, booleans).

        Examples
        --------
        >>> import numpy as np
        >>> from navkit.planning import ConicAttraction, KhatibRepulsion
        >>> ConicAttraction((3.0, 4.0)).force([0.0, 0.0])  # a unit pull toward the goal
        array([[0.6, 0.8]])
        >>> ConicAttraction((3.0, 4.0)).force(np.empty((0, 2))).shape
        (0, 2)

        Khatib's push ``k_rep (1/d - 1/d0) / d²`` away from the obstacle, zero
        beyond the influence radius:

        >>> field = KhatibRepulsion([[1.0, 0.0]], k_rep=1.0, influence_radius=1.0)
        >>> field.force([[0.5, 0.0], [3.0, 0.0]])
        array([[-4.,  0.],
               [ 0.,  0.]])
        """
        pts = points(points_xy, "points_xy")
        try:
            return self._force(pts)
        except FloatingPointError:
            return _redone(self._force, pts)

    @abstractmethod
    def _potential(self, pts: FloatArray) -> FloatArray: ...

    @abstractmethod
    def _force(self, pts: FloatArray) -> FloatArray: ...

    def _parts(self) -> tuple[PotentialField, ...]:
        return (self,)

    def __add__(self, other: PotentialField) -> CompositeField:
        if not isinstance(other, PotentialField):
            return NotImplemented
        return CompositeField((*self._parts(), *other._parts()))

    def __radd__(self, other: object) -> PotentialField:
        # Lets ``sum(fields)`` start from its integer 0.
        if isinstance(other, int) and other == 0:
            return self
        return NotImplemented

    def __repr__(self) -> str:
        # The dataclass fields shown by repr, arrays shortened (a point as a tuple).
        obj: object = self
        if not dataclasses.is_dataclass(obj):
            return object.__repr__(self)
        args = ", ".join(
            f"{f.name}={_short(getattr(self, f.name))}" for f in dataclasses.fields(obj) if f.repr
        )
        return f"{type(self).__name__}({args})"


def _redone(method: Callable[[FloatArray], FloatArray], pts: FloatArray) -> FloatArray:
    """``method(pts)`` again with underflow no error: NumPy's default answer.

    Only a caller's ``np.seterr(under="raise")`` makes a field's formula raise, where
    a squared offset of 1e-200 m underflows to 0. The formulas are pure, so they
    are evaluated again: a ``try`` costs nothing, an ``np.errstate`` per call more
    than a small field's formula.
    """
    with np.errstate(under="ignore"):
        return method(pts)


def _new_field(kind: type[PotentialField]) -> PotentialField:
    """An instance of ``kind`` not initialised, for its state to be set (``__reduce__``)."""
    return kind.__new__(kind)


def _checked_output(method: Any, name: str) -> Callable[[Any, FloatArray], FloatArray]:
    """A user field's ``_potential`` or ``_force`` (``name``), its input and output checked.

    Every caller (the public methods, a CompositeField's sum, sample_field, the
    controller) calls these directly on validated points, so the check sits here.
    ``method`` is the class attribute as defined: bound as Python would bind it
    (a staticmethod or classmethod as one, a callable that is no descriptor not at all).
    """
    force = name == "_force"
    bind = getattr(type(method), "__get__", None)

    @functools.wraps(method)
    def checked(self: Any, pts: FloatArray) -> FloatArray:
        # Read-only: the points may be the caller's own array, and a CompositeField
        # hands the same array to each of its fields in turn.
        view = pts.view()
        view.flags.writeable = False
        out = (method if bind is None else bind(method, self, type(self)))(view)
        shape = (pts.shape[0], 2) if force else (pts.shape[0],)
        if type(out) is np.ndarray and out.dtype == np.float64 and out.shape == shape:
            # The common case, without the conversions' cost (a few µs a call).
            ok = np.isfinite(out).all() if force else (out > -np.inf).all()
            if ok:
                return out.copy()
        where = f"{type(self).__name__}.{name}(points)"
        arr = as_float_array(out, where, shape=shape, finite=force)
        # NaN and -inf fail the comparison; +inf (an obstacle, as sample_field takes) passes.
        if not force and not bool((arr > -np.inf).all()):
            raise ValueError(f"{where} must not return NaN or -inf (+inf is allowed)")
        # The caller's own array: the field may keep (and later change) the one it
        # returned, or a view of it (an ndarray subclass, an object's __array__).
        return np.array(arr, copy=True)

    checked._navkit_checked = True  # type: ignore[attr-defined]
    return checked


def _short(value: Any) -> str:
    """Repr of a field value: a point as a tuple, a larger array by its shape."""
    if isinstance(value, np.ndarray):
        if value.ndim == 1:
            return "(" + ", ".join(repr(float(v)) for v in value) + ")"
        return f"<array shape={value.shape}>"
    return repr(value)


def _frozen(arr: FloatArray) -> FloatArray:
    """A read-only float64 copy (the caller's array is never frozen)."""
    out = np.array(arr, dtype=np.float64, copy=True)
    out.setflags(write=False)
    return out


def _restore(record: Any, state: Sequence[Any]) -> None:
    """``__setstate__`` of the frozen records here: fields from ``state``, arrays read-only.

    Pickles made before the records had a ``__reduce__`` hold the list
    of field values, restored through this; pickle and :func:`copy.deepcopy`
    hand the arrays back writable. Each frozen dataclass assigns this as
    ``__setstate__`` in its own body: the dataclass decorator replaces one it
    would inherit.

    A field pickled before the fields were dataclasses (5e5f83f and before, 23
    to 30 November 2026, in modules that moved: see :mod:`navkit._shared.moved`)
    comes as Python's ``(None, {slot: value})`` to a record with no field set:
    its values under today's names (the class's ``_renamed_fields``: ``goal``
    is ``goal_xy``, ``rad_thr`` ``threshold_radius``...), its caches (a
    repulsion's KD-tree) dropped, the fields it did not hold at their defaults
    (review 53: they raised AttributeError ``'rad_thr'``).
    """
    names = [f.name for f in dataclasses.fields(record)]
    if _slot_pickle(record, state, names):
        # Its caches (the repulsions' KD-tree of then) are not carried over: rebuilt.
        old = {name: value for name, value in state[1].items() if not name.startswith("_")}
        renamed: Mapping[str, str] = getattr(type(record), "_renamed_fields", {})
        held = {renamed.get(name, name) for name in old}
        for f in dataclasses.fields(record):
            if f.default is not dataclasses.MISSING and f.name not in held:
                old[f.name] = f.default
        restore_read_only(record, old, names)
        return
    restore_read_only(record, state, names)


def _slot_pickle(record: Any, state: Sequence[Any], names: Sequence[str]) -> bool:
    """Whether ``state`` is a pickle of a field made while it had plain slots.

    ``(None, {slot: value})``, Python's state of a slotted object, given to a
    record none of whose fields is set: :func:`~navkit._shared.frozen.reduce_record`'s
    tuple of what a subclass adds comes after the record is rebuilt.
    """
    return (
        isinstance(state, tuple)
        and len(state) == 2
        and state[0] is None
        and isinstance(state[1], dict)
        and not any(hasattr(record, name) for name in names)
    )


def _goal(goal_xy: ArrayLike) -> FloatArray:
    """A goal ``(x, y)`` as a read-only float64 copy, validated."""
    return _frozen(point(goal_xy, "goal_xy"))


def _obstacles(obstacles_xy: ArrayLike) -> FloatArray:
    """Obstacle points as a read-only ``(M, 2)`` float64 copy, validated."""
    return _frozen(points(obstacles_xy, "obstacles_xy"))


def _offsets(pts: FloatArray, centre: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Offsets ``pts - centre`` and their norms."""
    diff = pts - centre
    return diff, np.hypot(diff[:, 0], diff[:, 1])


# Below this distance (m) an offset may have subnormal components, whose hypot
# rounds by up to a factor of √2 (5e-324 on both axes has hypot 5e-324), so a
# direction divided by it would not be a unit vector; such offsets are scaled
# up by an exact power of two first.
_TINY_OFFSET = 1e-290
_RESCALE = 2.0**600


def _direction(dx: FloatArray, dy: FloatArray, d: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Components of ``(dx, dy) / d``, ``d = hypot(dx, dy)``; 0 where ``d == 0``.

    A unit vector wherever ``d > 0``, also for offsets of a few subnormals.
    """
    on = d == 0.0
    safe = np.where(on, 1.0, d)
    ux = np.where(on, 0.0, dx / safe)
    uy = np.where(on, 0.0, dy / safe)
    tiny = (d < _TINY_OFFSET) & ~on
    if tiny.any():
        sx = dx[tiny] * _RESCALE
        sy = dy[tiny] * _RESCALE
        norm = np.hypot(sx, sy)
        ux[tiny] = sx / norm
        uy[tiny] = sy / norm
    return ux, uy


def _unit(diff: FloatArray, d: FloatArray) -> FloatArray:
    """``diff / d`` row-wise (unit rows), with the zero vector where ``d == 0``."""
    ux, uy = _direction(diff[:, 0], diff[:, 1], d)
    return np.stack((ux, uy), axis=1)


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False, repr=False)
class CompositeField(PotentialField):
    """Sum of fields: potential and force add up.

    Usually built with ``+`` or ``sum(fields)``; nested sums are flattened.

    Parameters
    ----------
    fields : iterable of PotentialField
        The parts (a list, tuple or other ordered iterable; not a mapping, set
        or string), stored as a tuple; an empty one is the zero field.

    Raises
    ------
    TypeError
        ``fields`` not an iterable of PotentialField (a single field, a
        mapping, a str or a set included), naming the first item that is not one.

    Examples
    --------
    >>> from navkit.planning import ConicAttraction, KhatibRepulsion
    >>> total = ConicAttraction((5.0, 0.0)) + KhatibRepulsion([[1.0, 0.0]], influence_radius=2.0)
    >>> len(total.fields)
    2
    >>> total.force([[0.0, 0.0]])        # pulled +x by 1, pushed -x by (1 - 1/2)/1 = 0.5
    array([[0.5, 0. ]])
    >>> CompositeField([]).potential([0.0, 0.0])
    array([0.])
    """

    fields: tuple[PotentialField, ...]

    # As every field's: older pickles' field lists, and what a subclass adds after
    # the rebuild (reduce_record), where the dataclass's own would read it as fields.
    __setstate__ = _restore

    if TYPE_CHECKING:
        # The generated ``__init__`` takes any iterable (``__post_init__`` makes it a
        # tuple); this signature tells type checkers so, at no runtime cost.
        def __init__(self, fields: Iterable[PotentialField]) -> None: ...

    def __post_init__(self) -> None:
        given: object = self.fields
        if isinstance(given, (PotentialField, Mapping, str, bytes, set, frozenset)) or not (
            isinstance(given, Iterable)
        ):
            raise TypeError(
                f"fields must be an iterable of PotentialField, got {type(given).__name__}"
            )
        parts: list[PotentialField] = []
        for i, field in enumerate(given):
            if not isinstance(field, PotentialField):
                raise TypeError(f"fields[{i}] must be a PotentialField, got {type(field).__name__}")
            parts.extend(field._parts())
        object.__setattr__(self, "fields", tuple(parts))

    def _parts(self) -> tuple[PotentialField, ...]:
        return self.fields

    def _potential(self, pts: FloatArray) -> FloatArray:
        out = np.zeros(pts.shape[0], dtype=np.float64)
        for field in self.fields:
            out += field._potential(pts)
        return out

    def _force(self, pts: FloatArray) -> FloatArray:
        out = np.zeros((pts.shape[0], 2), dtype=np.float64)
        for field in self.fields:
            out += field._force(pts)
        return out
