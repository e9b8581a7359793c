"""Private input validation shared by every navkit layer.

Each helper converts its input to the type the numerical code needs and raises a
``ValueError`` or ``TypeError`` that names the offending argument — never another
exception type (an integer too large for a float is a ``ValueError``, not an
``OverflowError``). Arrays are returned as new float64/int64 arrays whenever a
conversion happens; callers that write into the result must copy explicitly
(``np.array(..., copy=True)``) so the caller's data is never modified.

What counts as a real number, everywhere: Python and NumPy integers and floats
(and 0-d arrays of them); not ``bool``, not complex numbers (even with a zero
imaginary part), not strings (even numeric ones such as ``"1.0"``), not ``None``.
``fractions.Fraction`` is real (``numbers.Real``); ``decimal.Decimal`` is not, and
is refused. Masked arrays and masked scalars with masked entries are refused
(NumPy's conversions would read the data under the mask); any other array-like
NumPy reads (byte-swapped, memory-mapped, broadcast, ``memoryview``,
``array.array``, objects with only ``__array__`` or ``__array_interface__``)
counts as its values, ``np.matrix`` as the 2-D array of its values. Arrays
handed to numba kernels go through :func:`kernel_input`, so that no layout
(read-only, strided) compiles a kernel a second time. No array a kernel may
receive keeps a misaligned buffer (:func:`aligned`, review 47): the float
converters (:func:`as_float_array`, :func:`as_points`) and :func:`kernel_input`
copy one.
"""

from __future__ import annotations

import math
import numbers
import sys
from collections.abc import Mapping, Sequence
from itertools import chain
from typing import Any, TypeGuard, TypeVar, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.types import FloatArray

_T = TypeVar("_T", bound=np.generic)

SMALLEST_POSITIVE = sys.float_info.min
"""The smallest positive value :func:`positive_float` accepts: the smallest normal
float64 (about 2.2e-308), so that ``1 / value`` is finite. Subnormal numbers such
as 5e-324 are > 0 but dividing by them overflows."""


def finite_float(value: Any, name: str) -> float:
    """Return ``value`` as a finite Python float or raise naming ``name``.

    ``bool``, complex numbers, strings and other non-real objects raise
    ``TypeError``; NaN, infinities and integers too large for a float raise
    ``ValueError``.
    """
    if type(value) is float:  # the common case, first
        if math.isfinite(value):
            return value
        raise ValueError(f"{name} must be finite, got {value}")
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        if is_ndarray(value) and value.ndim == 0 and value.dtype.kind in "fiu":
            # A masked scalar (np.ma.masked, an element of a masked array) has data
            # that stands for nothing: .item() would read it.
            refuse_masked(value, name)
            value = value.item()
        else:
            raise TypeError(f"{name} must be a real number, got {type(value).__name__}")
    try:
        out = float(value)
    except OverflowError:
        raise ValueError(
            f"{name} must be finite, got {_magnitude(value)}, too large for a float"
        ) from None
    if not math.isfinite(out):
        raise ValueError(f"{name} must be finite, got {out}")
    return out


def _magnitude(value: Any) -> str:
    """A short text for a huge number (its repr may have hundreds of digits)."""
    if isinstance(value, numbers.Integral):
        # str() of a huge int may itself refuse (sys.int_info.default_max_str_digits).
        return f"an integer of about 10**{int(int(value).bit_length() * math.log10(2))}"
    return type(value).__name__


def positive_float(value: Any, name: str, *, allow_zero: bool = False) -> float:
    """Return ``value`` as a finite float that is > 0 (or >= 0 with ``allow_zero``).

    "Positive" means at least :data:`SMALLEST_POSITIVE` (about 2.2e-308): a
    subnormal value such as 5e-324 is refused, since dividing by it overflows to
    infinity. With ``allow_zero``, 0 is accepted but subnormals still are not.
    """
    out = finite_float(value, name)
    if out < 0.0 or (out == 0.0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        raise ValueError(f"{name} must be {bound}, got {out}")
    if 0.0 < out < SMALLEST_POSITIVE:
        zero = "0 or " if allow_zero else ""
        raise ValueError(
            f"{name} must be {zero}at least {SMALLEST_POSITIVE:.4g} (a normal float), got {out!r}"
        )
    return out


def as_bool(value: Any, name: str) -> bool:
    """Return ``value`` as a Python bool; only ``bool`` and ``numpy.bool_`` are accepted."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be a bool, got {type(value).__name__}")
    return bool(value)


def bounded_int(
    value: Any,
    name: str,
    low: int | None = None,
    high: int | None = None,
    *,
    exclusive: bool = False,
    or_none: bool = False,
) -> int:
    """Return ``value`` as a Python int in ``[low, high]`` or raise naming ``name``.

    The one check of every integer option (counts, bits, levels, seeds, indices).
    Integers are Python ints, NumPy integer scalars and 0-d integer arrays
    (``np.array(3)``, what a reduction or an indexing of an integer array gives);
    ``bool`` and ``numpy.bool_`` are refused, and so are floats even when whole
    (``2.0``): a ``TypeError``. A value outside the range is a ``ValueError``
    that states the range.

    Parameters
    ----------
    value : object
        The caller's argument.
    name : str
        Its name, as the caller wrote it, for the messages.
    low, high : int, optional
        The smallest and largest values accepted; ``None`` leaves that side open.
    exclusive : bool, default False
        ``high`` itself is refused (an index below a length, a seed below 2**64).
    or_none : bool, default False
        Only the wording: the caller accepts ``None`` itself, and the type message
        says so ("an integer or None").

    Examples
    --------
    >>> bounded_int(np.array(3), "levels", 1, 8)
    3
    >>> bounded_int(2**64, "seed", 0, 2**64, exclusive=True)
    Traceback (most recent call last):
    ...
    ValueError: seed must be in [0, 2**64), got 18446744073709551616
    >>> bounded_int(np.True_, "bits")
    Traceback (most recent call last):
    ...
    TypeError: bits must be an integer, got bool
    """
    if type(value) is int:  # the common case, first
        out = value
    elif _is_integer(value):
        out = int(value)
    elif is_ndarray(value) and value.ndim == 0 and value.dtype.kind in "iu":
        refuse_masked(value, name)
        out = int(value.item())
    else:
        what = "an integer or None" if or_none else "an integer"
        raise TypeError(f"{name} must be {what}, got {type(value).__name__}")
    too_low = low is not None and out < low
    too_high = high is not None and (out >= high if exclusive else out > high)
    if too_low or too_high:
        got = str(out) if abs(out) < 10**30 else _magnitude(out)
        raise ValueError(f"{name} must be {_int_range(low, high, exclusive)}, got {got}")
    return out


def _int_range(low: int | None, high: int | None, exclusive: bool) -> str:
    if high is None:
        return f">= {_bound_text(low)}"
    if low is None:
        return f"{'<' if exclusive else '<='} {_bound_text(high)}"
    return f"in [{_bound_text(low)}, {_bound_text(high)}{')' if exclusive else ']'}"


def _bound_text(value: int | None) -> str:
    """A range end for a message: 2**64 and 2**63 - 1 read better as powers."""
    if value is not None and value >= 2**32:
        if value & (value - 1) == 0:
            return f"2**{value.bit_length() - 1}"
        if (value + 1) & value == 0:
            return f"2**{value.bit_length()} - 1"
    return str(value)


#: NumPy's most dimensions (64 since NumPy 2, 32 before): deeper nestings are no array.
_MAX_DEPTH = 64


_SEQUENCES = {list, tuple}
_FLOAT64 = np.dtype(np.float64)


def holds_bool(value: list[Any] | tuple[Any, ...], top_types: set[type] | None = None) -> bool:
    """Whether nested lists or tuples hold a bool (or a bool array) at any depth.

    One nesting level at a time, with C-level loops (``map``, ``chain``): about
    as fast as NumPy's own conversion of the lists. Not below NumPy's 64
    dimensions (deeper lists, or one that contains itself, are no array).
    ``top_types``, the types of ``value``'s elements, spares computing them again.
    """
    items: list[Any] | tuple[Any, ...] = value
    for _ in range(_MAX_DEPTH + 1):
        types = set(map(type, items)) if top_types is None else top_types
        top_types = None
        if bool in types or np.bool_ in types:
            return True
        if any(issubclass(kind, np.ndarray) for kind in types) and any(
            item.dtype.kind == "b" for item in items if issubclass(type(item), np.ndarray)
        ):
            return True
        if not types or not types <= _SEQUENCES:
            return False  # numbers (or ragged nesting, which the conversion refuses)
        items = list(chain.from_iterable(items))
    return False


class _Block:
    """Stand-in for a regular (non-object) NumPy array of ``shape``: no element is read."""

    __slots__ = ("shape",)

    def __init__(self, shape: tuple[int, ...]) -> None:
        self.shape = shape


def is_ragged(value: Any) -> bool:
    """Whether ``value`` nests lists, tuples or arrays of different lengths at one depth.

    A string or bytes at a depth reached makes it False: those are a type
    error, reported as such by the converters. So does a nesting deeper than
    NumPy's 64 dimensions (an array cannot have them, whatever the lengths),
    which also ends the walk of a list that contains itself. Only called once
    a conversion has failed, so a successful one pays nothing for it.

    Examples
    --------
    >>> is_ragged([[1, 2], [3, 4]]), is_ragged([1, [2, 3]]), is_ragged([[1, 2], "ab"])
    (False, True, False)
    """
    level: list[Any] = [value]
    for _ in range(_MAX_DEPTH + 1):
        lengths: set[int] = set()
        scalars = False
        deeper: list[Any] = []
        for item in level:
            if isinstance(item, (str, bytes)):
                return False
            if isinstance(item, _Block) or (
                issubclass(type(item), np.ndarray) and item.dtype.kind != "O"
            ):
                if not item.shape:
                    scalars = True
                    continue
                lengths.add(item.shape[0])
                # Every row has the shape of the first; an empty block's rows still
                # have a shape that must agree with its neighbours' (numpy checks it).
                deeper.append(_Block(item.shape[1:]))
            elif isinstance(item, (list, tuple)) or issubclass(type(item), np.ndarray):
                if issubclass(type(item), np.ndarray) and item.ndim == 0:
                    scalars = True
                    continue
                lengths.add(len(item))
                deeper.extend(item)
            else:
                scalars = True
        if not lengths:
            return False
        if scalars or len(lengths) > 1:
            return True
        level = deeper
    return False


def _not_an_array(value: Any, name: str, exc: Exception) -> Exception:
    """The error for a ``value`` NumPy could not convert: ragged nesting is a wrong shape."""
    if is_ragged(value):
        return ValueError(
            f"{name} must be a rectangular array, got nested sequences of different "
            "lengths (ragged)"
        )
    return TypeError(f"{name} must be numeric array-like: {exc}")


def as_array(value: ArrayLike, name: str) -> NDArray[Any]:
    """``np.asarray(value)``, a failure an error naming ``name``.

    A ragged nesting (``[[1, 2], [3]]``) is a ``ValueError``, anything else
    NumPy cannot convert a ``TypeError``.

    Examples
    --------
    >>> as_array([[True, False]], "mask").dtype
    dtype('bool')
    >>> as_array([[1, 2], [3]], "mask")
    Traceback (most recent call last):
    ...
    ValueError: mask must be a rectangular array, got nested sequences of different lengths (ragged)
    """
    refuse_masked(value, name)
    try:
        return np.asarray(value)
    except (TypeError, ValueError) as exc:
        raise _not_an_array(value, name, exc) from None


def refuse_masked(value: object, name: str) -> None:
    """Refuse a masked array with masked entries: NumPy's conversions drop the mask.

    ``np.asarray`` of a masked array is its data, masked entries included, so a
    mask meant as "no value here" would be silently ignored. A masked array
    without masked entries is its data and passes.

    Examples
    --------
    >>> refuse_masked(np.ma.masked_invalid([1.0, np.nan]), "ranges")
    Traceback (most recent call last):
    ...
    ValueError: ranges has masked entries, which would be read as their data: ...
    """
    # .mask is np.ma.nomask (False) or a boolean array of the data's shape.
    if issubclass(type(value), np.ma.MaskedArray) and _any_masked(
        cast("np.ma.MaskedArray[Any, Any]", value)
    ):
        raise ValueError(
            f"{name} has masked entries, which would be read as their data: "
            "fill them first (masked_array.filled(value))"
        )
    if isinstance(value, (list, tuple)):
        _refuse_masked_elements(value, name, set(map(type, value)))


def _any_masked(value: np.ma.MaskedArray[Any, Any]) -> bool:
    """Whether ``value`` has a masked entry (a field of one, for a structured array).

    The mask of a structured array is structured too (a boolean per field), which
    ``np.any`` cannot reduce: it raised an unnamed ``TypeError`` ("Iterator operand
    1 dtype could not be cast") before the callers' dtype check could name the
    argument.
    """
    return _any_set(value.mask)


def _any_set(mask: Any) -> bool:
    """Whether a mask (``nomask``, a boolean array, or a structured one, nested) has a True."""
    names = None if mask is np.ma.nomask else mask.dtype.names
    if names is None:
        return bool(np.any(mask))
    return any(_any_set(mask[name]) for name in names)


def _refuse_masked_elements(
    value: list[Any] | tuple[Any, ...], name: str, types: set[type]
) -> None:
    """:func:`refuse_masked` for the elements of a list, ``types`` their types.

    Only the top level, as ``np.ma.array`` reads a list: ``[np.ma.masked, 1.0]``
    or a list of masked rows. NumPy's conversions read masked entries as their
    data (the ``np.ma.masked`` constant as NaN, with a warning).
    """
    if any(issubclass(kind, np.ma.MaskedArray) for kind in types):
        for item in value:
            if issubclass(type(item), np.ma.MaskedArray) and _any_masked(item):
                raise ValueError(
                    f"{name} has masked entries (in an element of the list), which would "
                    "be read as their data: fill them first (masked_array.filled(value))"
                )


def _real_array(value: Any, name: str, components: int | None = None) -> FloatArray:
    """``value`` as float64, refusing what only converts by accident.

    Complex numbers (NumPy would drop the imaginary part with a warning),
    strings (``"1.0"`` converts silently) and booleans are rejected, consistently
    with :func:`finite_float`. ``components`` (the length of the last axis the
    caller wants, if known) only shapes the hint for a ROS message given whole.
    """
    kind_of = type(value)
    # The type itself, not isinstance: an object whose ``__class__`` says ndarray
    # (a ``Mock(spec=np.ndarray)``, a wrapper) has none of its attributes; it is
    # read by np.asarray below as any array-like is (review 36).
    if kind_of is np.ndarray or issubclass(kind_of, np.ndarray):
        if kind_of is not np.ndarray:
            refuse_masked(value, name)
        kind = value.dtype.kind
        if value.dtype is _FLOAT64:
            # aligned(), inlined (the common case: a call less): a float64 array's
            # buffer is used as it is (a subclass's as a plain view), misaligned or not.
            out = np.asarray(value)
            return out if out.flags.aligned else out.copy()
        if kind in "iu":
            return np.asarray(value, dtype=np.float64)  # a new array: aligned
        if kind == "f":
            # Widening a signalling NaN (float32 from a driver or a bag) makes NumPy
            # warn "invalid value encountered in cast"; it is still a NaN. A long
            # double beyond float64's range warns "overflow": it is an infinity,
            # which the finiteness check names.
            with np.errstate(invalid="ignore", over="ignore"):
                return aligned(np.asarray(value, dtype=np.float64))
        if kind != "O":
            raise TypeError(f"{name} must hold real numbers, got dtype {value.dtype}")
    elif isinstance(value, (str, bytes, complex, bool, np.bool_, np.complexfloating)):
        raise TypeError(f"{name} must be numeric array-like, got {type(value).__name__}")
    elif isinstance(value, (list, tuple)):
        types = set(map(type, value))  # once, for both checks
        _refuse_masked_elements(value, name, types)
        if holds_bool(value, types):
            # NumPy would turn [True, 0.5] into [1.0, 0.5] (only all-bool lists stay bool).
            raise TypeError(f"{name} must hold real numbers, got an element of type bool")
    try:
        raw = np.asarray(value)
    except (TypeError, ValueError) as exc:
        raise _not_an_array(value, name, exc) from None
    kind = raw.dtype.kind
    if kind == "O":
        for item in raw.ravel():
            if isinstance(item, (bool, np.bool_)) or not isinstance(item, numbers.Real):
                raise TypeError(
                    f"{name} must hold real numbers, got an element of type {type(item).__name__}"
                    + _message_hint(item, components)
                )
    elif kind not in "iuf":
        raise TypeError(f"{name} must hold real numbers, got dtype {raw.dtype}")
    try:
        if kind == "f" and raw.dtype.itemsize != 8:
            # As for an ndarray above: a long double that overflows, a float32
            # signalling NaN that warns (review 30). Lists of Python floats, float64,
            # cast nothing and skip the errstate.
            with np.errstate(invalid="ignore", over="ignore"):
                return np.asarray(raw, dtype=np.float64)
        # A memoryview or an __array_interface__ object may give bytes at any offset.
        return aligned(np.asarray(raw, dtype=np.float64))
    except OverflowError:
        raise ValueError(
            f"{name} must hold finite numbers, got an integer too large for a float"
        ) from None
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be numeric array-like: {exc}") from None


def _navkit_names(value: object) -> set[str]:
    """The names of the navkit classes among the bases of ``value``'s type."""
    return {k.__name__ for k in type(value).__mro__ if k.__module__.startswith("navkit.")}


def scan_reading_hint(value: object) -> str:
    """A hint for a simulated ``ScanReading`` passed where its ``LaserScan`` is wanted, or ``""``.

    A :class:`navkit.sim.Observation`'s ``scan`` is the reading (its ``stamp`` and
    its ``scan``), not the scan itself, so a controller handing ``obs.scan`` on to
    a mapper, a matcher or a repulsion was told only that it is not a LaserScan
    (review 52). Told by the type's name, as :func:`_points_hint` (this layer
    imports neither class).

    Examples
    --------
    >>> scan_reading_hint(3.0)
    ''
    """
    if "ScanReading" in _navkit_names(value):
        return " (a simulated reading: its .scan is the LaserScan, e.g. obs.scan.scan)"
    return ""


def _points_hint(item: object) -> str:
    """A hint for a navkit ``Path2D`` or ``LaserScan`` passed whole where points are wanted.

    Told by their type's name and module (this layer imports neither): review 34
    found an integrator passing a planner's route to ``world_to_cell`` and a scan
    to ``LocalGrid.from_points``. A subclass (a user's ``Route(Path2D)``) is one
    too: every navkit class among its bases is looked at.
    """
    names = _navkit_names(item)
    if "ScanReading" in names:
        return (
            " (a simulated reading: its .scan is the LaserScan, e.g. obs.scan.scan;"
            " its end points are reading.scan.to_points(pose))"
        )
    if "Path2D" in names:
        return " (a whole path: pass path.points, (K, 2) in the frame path.frame names)"
    if "LaserScan" in names:
        return (
            " (a whole scan: pass its end points, scan.to_points(pose) in the world"
            " or scan.to_points() in the sensor frame)"
        )
    return ""


def _message_hint(item: object, components: int | None = None) -> str:
    """A hint for a ROS message (``geometry_msgs/Point``, ``Quaternion``, ...) passed whole.

    With ``components`` (the values the argument takes per item), only that many
    fields are suggested: a ``Point`` where points ``(x, y)`` are wanted is
    ``(m.x, m.y)``, not ``(m.x, m.y, m.z)``, which would be refused for its shape.
    """
    if components == 2:  # an argument of (x, y) points
        hint = _points_hint(item)
        if hint:
            return hint
    try:
        fields = [f for f in "xyzw" if hasattr(item, f)]
    except Exception:  # a property raising: not a message
        return ""
    if fields[:2] != ["x", "y"]:
        return ""
    if components is not None and components > len(fields):
        return ""  # not the message the argument wants: no advice beats a wrong one
    if type(item).__module__.startswith("navkit"):  # a Pose2D, say: named as what it is
        listed = ", ".join(f"p.{f}" for f in fields[:components])
        return f" with fields {', '.join(fields)}: pass ({listed}) of that {type(item).__name__} p"
    listed = ", ".join(f"m.{f}" for f in fields[:components])
    return f" with fields {', '.join(fields)} (a ROS message?): pass ({listed})"


def integer_readings(value: object, name: str) -> NDArray[Any]:
    """``value`` as an integer array (unconverted), or a TypeError naming ``name``.

    For counter readings (encoder ticks), whose range the caller checks. Integers
    that NumPy gives no integer dtype (an empty list is float64, ints beyond 64
    bits are objects, ``[2**64 - 1, -1]`` is float64) come back as an object
    array of Python ints, so that the caller's range check refuses the ones out
    of range with a ValueError rather than their dtype with a TypeError.
    Booleans, alone or mixed into lists (NumPy turns ``[True, 5]`` into
    ``[1, 5]``), are refused. A ragged nesting (``[[1, 2], [3]]``) is a wrong
    shape, a ValueError, as in :func:`as_array`.
    """
    if isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must hold integer counter readings, got {type(value).__name__}")
    if isinstance(value, (list, tuple)):
        types = set(map(type, value))  # once, for both checks
        _refuse_masked_elements(value, name, types)
        if holds_bool(value, types):
            raise TypeError(
                f"{name} must hold integer counter readings, got an element of type bool"
            )
    else:
        refuse_masked(value, name)  # np.asarray would read masked readings as their data
    try:
        arr = np.asarray(value)
    except (TypeError, ValueError, OverflowError) as exc:
        if is_ragged(value):  # a wrong shape, as for every other array argument
            raise _not_an_array(value, name, exc) from None
        raise TypeError(f"{name} must hold integer counter readings: {exc}") from None
    kind = arr.dtype.kind
    if kind in "iu":
        return arr
    if kind == "O" or (kind == "f" and not issubclass(type(value), np.ndarray)):
        items = arr if kind == "O" else np.asarray(value, dtype=object)
        if all(_is_integer(item) for item in items.flat):
            return items
    hint = ""
    if kind == "f":
        # Review 34: a ROS robot's wheels arrive as sensor_msgs/JointState angles.
        hint = (
            " (encoder counts are integers; wheel angles in radians, as a ROS"
            " sensor_msgs/JointState gives them, are not counts: step"
            " DiffDrive.odometry_step with the distances rolled, wheel radius times"
            " each angle's change)"
        )
    raise TypeError(f"{name} must hold integer counter readings, got dtype {arr.dtype}{hint}")


def _is_integer(item: object) -> bool:
    return isinstance(item, numbers.Integral) and not isinstance(item, (bool, np.bool_))


def as_float_array(
    value: ArrayLike,
    name: str,
    *,
    ndim: int | None = None,
    shape: Sequence[int | None] | None = None,
    finite: bool = True,
    components: int | None = None,
) -> FloatArray:
    """Convert ``value`` to a float64 array and check its shape and finiteness.

    Parameters
    ----------
    value : array_like
        Input data.
    name : str
        Argument name used in error messages.
    ndim : int, optional
        Required number of dimensions.
    shape : sequence of int or None, optional
        Required shape; ``None`` entries match any length. Implies ``ndim``.
    finite : bool, default True
        Reject NaN and infinities.
    components : int, optional
        Values per item (the last axis's length) the caller wants when
        ``shape`` does not say (``shape[-1]`` by default): the fields suggested
        when a ROS message is passed whole.
    """
    if components is None and shape is not None and len(shape) > 0:
        components = shape[-1]
    arr = _real_array(value, name, components)
    if arr.ndim == 1 and arr.shape[0] > 1 and arr.strides[0] <= 0:
        # A broadcast (np.broadcast_to) or reversed view: NumPy's products (`@`) take
        # another summation order for it than BLAS does for the same values in a
        # plain array, so results would differ in the last bits with the layout.
        arr = np.ascontiguousarray(arr)
    if shape is not None:
        ndim = len(shape)
    if ndim is not None and arr.ndim != ndim:
        raise ValueError(f"{name} must be {ndim}-D, got shape {arr.shape}" + _ndim_hint(arr, ndim))
    if shape is not None:
        for axis, (got, want) in enumerate(zip(arr.shape, shape, strict=True)):
            if want is not None and got != want:
                raise ValueError(
                    f"{name} must have length {want} along axis {axis}, got shape {arr.shape}"
                    + transposed_hint(arr.shape, shape)
                )
    if finite and not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must contain only finite values")
    return arr


def kernel_input(arr: FloatArray) -> FloatArray:
    """``arr`` as the C-contiguous, writeable, aligned float64 array the kernels are compiled for.

    numba compiles a kernel once per array type, and a read-only array (a
    memory map opened with mode ``"r"``, ``np.frombuffer`` of a message's bytes,
    a broadcast view) or a non-contiguous one is another type than the fresh
    arrays the kernels are warmed up with: passed as it is, it would pay a
    compilation (hundreds of ms) on its first call. A misaligned one is
    typed as an aligned array (see :func:`aligned`). Such arrays are copied
    (the caller's buffer is then not read by the kernel at all); others pass
    as they are.

    Examples
    --------
    >>> frozen = np.zeros(3)
    >>> frozen.flags.writeable = False
    >>> kernel_input(frozen).flags.writeable
    True
    >>> odd = np.frombuffer(bytearray(25), dtype=np.float64, count=3, offset=1)
    >>> odd.flags.aligned, kernel_input(odd).flags.aligned
    (False, True)
    """
    # carray: C-contiguous, aligned and writeable, in one flag test.
    if arr.flags.carray and arr.dtype == _FLOAT64:
        return arr
    return np.array(arr, dtype=np.float64, order="C")


def aligned(arr: NDArray[_T]) -> NDArray[_T]:
    """``arr`` itself, or a C-contiguous copy of it if its buffer is not aligned for its dtype.

    The rule for every array a numba kernel may receive (review 47): numba
    types a misaligned array (a float64 view of bytes at an odd offset, from
    ``np.frombuffer`` of a message or a file; a float64 field of a packed
    structured array) as an *aligned* one, and LLVM then assumes its loads
    aligned: undefined behaviour (x86-64 and AArch64 execute such loads all
    the same; a vectoriser may emit aligned SIMD loads, other targets trap).
    ``np.ascontiguousarray`` and ``np.asarray(..., dtype=...)`` keep a
    misaligned buffer as it is when no conversion is needed. An aligned
    array costs one flag test; a copy is made only for a misaligned one,
    and the input is never modified.

    Examples
    --------
    >>> odd = np.frombuffer(bytes(25), dtype=np.float64, count=3, offset=1)
    >>> odd.flags.aligned, aligned(odd).flags.aligned
    (False, True)
    >>> plain = np.zeros(3)
    >>> aligned(plain) is plain
    True
    """
    if arr.flags.aligned:
        return arr
    return arr.copy()


def as_points(value: ArrayLike, name: str, *, finite: bool = True) -> FloatArray:
    """Convert ``value`` to an ``(N, 2)`` float64 array of points.

    A single point of shape ``(2,)`` becomes ``(1, 2)``; no points — an empty
    sequence (shape ``(0,)``) or shape ``(0, 2)`` — become ``(0, 2)``. Other
    empty shapes (``(3, 0)``, ``(0, 3)``, ``(0, 0)``) are mistakes and raise.
    """
    arr = as_float_array(value, name, finite=finite, components=2)
    if arr.ndim == 2 and arr.shape[1] == 2:
        return arr
    if arr.shape == (2,):
        return arr.reshape(1, 2)
    if arr.shape == (0,):
        return np.empty((0, 2), dtype=np.float64)
    raise ValueError(
        f"{name} must have shape (N, 2) or (2,), got {arr.shape}"
        + (_POSE_HINT if arr.shape == (3,) else transposed_hint(arr.shape, (None, 2)))
    )


# One pose [x, y, theta] where one point is wanted: the 1-D form of the
# transposed_hint's rows of poses (review 53: FieldDStar.plan_world given a pose).
_POSE_HINT = " (a pose [x, y, theta]? pass its [:2])"


def as_point(value: ArrayLike, name: str) -> FloatArray:
    """``value`` as one finite world point ``(x, y)``: a float64 array of shape ``(2,)``.

    The checks and messages of ``as_float_array(value, name, shape=(2,))``,
    and for a pose ``(x, y, theta)`` given where a point is wanted, the way
    out (its ``[:2]``), as :func:`transposed_hint` names rows of poses given
    where points are wanted. A :class:`~navkit.geometry.Pose2D` is refused
    with its own hint (see :func:`as_float_array`).

    Examples
    --------
    >>> as_point((1.0, 2.0), "start_xy")
    array([1., 2.])
    >>> as_point((1.0, 2.0, 0.5), "start_xy")
    Traceback (most recent call last):
        ...
    ValueError: start_xy must have length 2 along axis 0, got shape (3,) (a pose [x, y, theta]? ...
    """
    arr = as_float_array(value, name, finite=False, components=2)
    if arr.ndim != 1:
        raise ValueError(f"{name} must be 1-D, got shape {arr.shape}" + _ndim_hint(arr, 1))
    if arr.shape[0] != 2:
        raise ValueError(
            f"{name} must have length 2 along axis 0, got shape {arr.shape}"
            + (_POSE_HINT if arr.shape[0] == 3 else "")
        )
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must contain only finite values")
    return arr


def _ndim_hint(arr: NDArray[Any], ndim: int) -> str:
    """A hint for a scalar or a column/row vector given where a 1-D array is wanted."""
    if ndim != 1:
        return ""
    if arr.ndim == 0:
        return " (wrap a single value in a list: [value])"
    if arr.ndim == 2 and 1 in arr.shape:
        return " (a column or row vector: pass it flattened, e.g. np.ravel(value))"
    return ""


def transposed_hint(got: tuple[int, ...], want: Sequence[int | None]) -> str:
    """A hint for the common ``(k, N)``-for-``(N, k)`` mistake, or ``""``.

    Column-per-point layouts (MATLAB, some plotting code) are the usual cause;
    the hint is given only when the transpose has exactly the wanted shape.
    Where points ``(N, 2)`` are wanted, an ``(N, 3)`` array is more often rows
    of poses ``[x, y, theta]`` (``ScanMapper.trajectory``, ``Trace.poses``,
    ``BagOdometry.poses``), so that is named first: for two poses, shape
    ``(2, 3)``, the transpose alone would read them as three wrong points.

    Examples
    --------
    >>> transposed_hint((5, 3), (None, 2))
    ' (rows of poses [x, y, theta]? pass its [:, :2], shape (5, 2))'
    >>> transposed_hint((2, 7), (None, 2))
    ' (it looks transposed, one column per item: pass its .T, shape (7, 2))'
    """
    two_d = len(got) == 2 and len(want) == 2 and want[0] is None and want[1] is not None
    if not two_d:
        return ""
    transposed = got[0] == want[1] and got[1] != want[1]
    if want[1] == 2 and got[1] == 3:
        poses = f"rows of poses [x, y, theta]? pass its [:, :2], shape {(got[0], 2)}"
        if transposed:
            other = f"or, if it is transposed, one column per item, its .T, shape {got[::-1]}"
            return f" ({poses}; {other})"
        return f" ({poses})"
    if transposed:
        return f" (it looks transposed, one column per item: pass its .T, shape {got[::-1]})"
    return ""


def unpack(value: Any, name: str) -> tuple[Any, ...]:
    """``tuple(value)``, also for a multi-dimensional ``memoryview``.

    Python cannot iterate over a memoryview of more than one dimension or of a
    non-native format such as big-endian ``">d"`` (it raises
    ``NotImplementedError``): a memoryview gives the items (rows) of the array
    NumPy reads from it, as does an object NumPy reads only through its array
    protocols (:func:`has_array_protocol`); an ``np.matrix`` gives 1-D rows, as
    the array of its values does. Anything that is
    not iterable raises ``TypeError``, as ``tuple`` does (naming ``name`` only
    for a memoryview NumPy cannot read: callers word their own message).

    Examples
    --------
    >>> len(unpack(memoryview(np.zeros((2, 3))), "pairs"))
    2
    """
    kind = type(value)
    if kind is tuple or kind is list:  # the common case, first
        return tuple(value)
    if isinstance(value, np.matrix):
        value = np.asarray(value)  # a matrix's rows are 1-row matrices, not 1-D rows
    elif kind is memoryview or (
        not issubclass(kind, (list, tuple, np.ndarray)) and has_array_protocol(value)
    ):
        # Python iterates over a memoryview of one dimension only, and not over a
        # non-native format (big-endian ">d" from a file or a message: it raises
        # NotImplementedError); an object with only __array__ is not iterable.
        try:
            value = np.asarray(value)
        except (TypeError, ValueError, NotImplementedError) as exc:  # a format NumPy cannot read
            what = "a memoryview" if kind is memoryview else "an array"
            raise TypeError(f"{name} is {what} NumPy cannot read: {exc}") from None
    return tuple(value)


def is_ndarray(value: object) -> TypeGuard[NDArray[Any]]:
    """Whether ``value`` is a NumPy array (or a subclass's) by its type.

    Not ``isinstance``, which believes an object's ``__class__``: a
    ``unittest.mock.Mock(spec=np.ndarray)`` or a wrapper whose ``__class__``
    says ``np.ndarray`` passed and then lacked ``.dtype``/``.ndim`` (an
    ``AttributeError``); such objects are array-likes like any other, read
    through ``np.asarray`` or refused naming the argument (review 36). Hot
    paths spell it inline: ``issubclass(type(value), np.ndarray)``.

    Examples
    --------
    >>> from unittest import mock
    >>> is_ndarray(np.zeros(2)), is_ndarray(np.ma.array([1.0]))
    (True, True)
    >>> is_ndarray(mock.Mock(spec=np.ndarray)), is_ndarray([1.0])
    (False, False)
    """
    return issubclass(type(value), np.ndarray)


def has_array_protocol(value: object) -> bool:
    """Whether NumPy reads ``value`` as an array through one of its protocols.

    ``__array__`` (NumPy 2's ``copy=`` keyword included), ``__array_interface__``
    or ``__array_struct__``: a foreign array type (a tensor, the buffer of a
    message) that need not be a Python sequence. Arguments that take "a
    sequence of numbers" accept these as ``np.asarray`` reads them, as every
    array argument does. A NumPy scalar (``np.float64(1.0)``, which has the
    protocols too) is a number, not an array, as is the Python ``float`` it
    subclasses; a class is not an array either.

    Examples
    --------
    >>> class Wrapped:
    ...     def __array__(self, dtype=None, copy=None):
    ...         return np.zeros(3)
    >>> has_array_protocol(Wrapped()), has_array_protocol([1.0, 2.0])
    (True, False)
    >>> has_array_protocol(np.float64(1.0)), has_array_protocol(np.ndarray)
    (False, False)
    """
    if isinstance(value, (np.generic, type)):
        return False
    # On the instance, as NumPy looks all three up: an ``__array__`` set on an object
    # (not its class) is read by np.asarray, and was refused here (review 43, MUTANT15).
    return (
        hasattr(value, "__array__")
        or hasattr(value, "__array_interface__")
        or hasattr(value, "__array_struct__")
    )


def shown(value: object) -> str:
    """``repr(value)`` for a message, NumPy scalars written as the numbers they hold.

    NumPy 2 writes its scalars with their type (``np.float64(1.5)``), so a
    message quoting a tuple built from an array (``tuple(xy)``) read
    ``got (np.float64(1.5), np.float64(2.0))``. Tuples and lists are followed
    one level in; anything else is its own ``repr``.

    Examples
    --------
    >>> shown((np.float64(1.5), np.int64(2))), shown(np.True_), shown([np.float32(0.5)])
    ('(1.5, 2)', 'True', '[0.5]')
    >>> shown(np.array([1.5]))
    'array([1.5])'
    """
    if isinstance(value, np.generic):
        return repr(value.item())
    if type(value) is tuple or type(value) is list:
        items = [x.item() if isinstance(x, np.generic) else x for x in value]
        return repr(tuple(items) if type(value) is tuple else items)
    return repr(value)


def as_cell(value: Any, name: str, shape: tuple[int, ...]) -> tuple[int, int]:
    """Convert ``value`` to an integer ``(row, col)`` inside an array of ``shape``."""
    if isinstance(value, (str, bytes, Mapping, set, frozenset)):
        raise TypeError(f"{name} must be a (row, col) pair, got {type(value).__name__}")
    try:
        seq = unpack(value, name)
    except TypeError:
        raise TypeError(f"{name} must be a (row, col) pair, got {shown(value)}") from None
    if len(seq) != 2:
        raise ValueError(f"{name} must be a (row, col) pair, got {shown(value)}")
    cell: list[int] = []
    for item in seq:
        if isinstance(item, (bool, np.bool_)):
            raise TypeError(f"{name} must hold integers, got {shown(value)}")
        if not isinstance(item, numbers.Integral):
            # Integral floats (2.0, from arithmetic on coordinates) are accepted.
            if isinstance(item, numbers.Real) and math.isfinite(item) and float(item).is_integer():
                item = int(float(item))
            elif isinstance(item, numbers.Real):
                raise TypeError(
                    f"{name} must hold integers, got {shown(value)}: a cell is an integer "
                    "(row, col) index; convert a world point (x, y) in metres with "
                    "world_to_cell, or plan in metres with MapPlanner"
                )
            else:
                raise TypeError(f"{name} must hold integers, got {shown(value)}")
        cell.append(int(item))
    row, col = cell
    if not (0 <= row < shape[0] and 0 <= col < shape[1]):
        hint = ""
        if 0 <= col < shape[0] and 0 <= row < shape[1]:
            # The swapped pair fits: the usual cause is an (x, y) order.
            hint = f"; cells are (row, col), and {(col, row)} is inside: was it given as (x, y)?"
        raise ValueError(f"{name} {(row, col)} is outside the grid of shape {shape[:2]}{hint}")
    return row, col


def as_sequence(value: Any, name: str) -> tuple[Any, ...]:
    """The items of ``value``, an iterable other than a string or a mapping, as a tuple.

    Strings, bytes and mappings iterate over characters or keys, which no
    argument that wants a sequence of objects means: they are refused with the
    rest (``TypeError`` naming ``name``). The items themselves are the caller's
    to check.

    Examples
    --------
    >>> as_sequence([1, 2], "scans")
    (1, 2)
    >>> as_sequence(None, "scans")
    Traceback (most recent call last):
    ...
    TypeError: scans must be a sequence, got NoneType
    """
    if isinstance(value, (str, bytes, Mapping)):
        raise TypeError(f"{name} must be a sequence, got {type(value).__name__}")
    if type(value) is memoryview:
        return unpack(value, name)
    try:
        items = iter(value)
    except TypeError:
        raise TypeError(f"{name} must be a sequence, got {type(value).__name__}") from None
    return tuple(items)
