"""Foreign array types and array-likes for every array argument of the fuzz specs (review 19).

Users pass navkit whatever their code holds: masked arrays, ``np.matrix``,
big-endian buffers from a file or a ROS message, memory maps, views with
negative, Fortran or zero strides, objects that only expose ``__array__`` or
``__array_interface__``, ``array.array``, ``memoryview``, lists of NumPy
scalars, and scalars as ``Fraction``, NumPy scalar types or 0-d arrays.

Each :class:`Variant` turns the valid value of a spec's argument into a foreign
spelling and gives the plain (float64 C-contiguous, or Python float) value it
stands for. :func:`check_variant` calls the spec with both and says what went
wrong, if anything:

* ``same`` variants must give the plain value's answer bit for bit (the same
  result and the same receiver state; the same error type if the plain value is
  refused), or be refused with a ``ValueError``/``TypeError``/navkit error
  only where the variant says a refusal is allowed (``np.matrix`` for a 1-D
  argument: it is 2-D);
* ``reject`` variants (masked entries, complex values, ``Decimal``) must raise
  a ``ValueError``/``TypeError``;
* never another exception type, a change of the foreign input (memory-mapped
  files included), a result that shares memory with the caller's buffer, or a
  new numba kernel specialisation for the foreign layout or dtype.
"""

from __future__ import annotations

import array
import contextlib
import decimal
import fractions
import math
import sys
import tempfile
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from fuzz_engine import (
    SKIP,
    SPECS,
    Array,
    Cell,
    Ctx,
    Flag,
    Hang,
    PoseLike,
    Real,
    Spec,
    is_navkit_object,
    materialize,
    memory_limit,
    public_state,
    replace,
    same,
    slots,
    snapshot,
    watchdog,
)

from navkit.errors import NavkitError

SAME = "same"
REJECT = "reject"

POLICY = """
What each foreign spelling must give (review 19):

* Always accepted, as the values NumPy reads: masked arrays without masked
  entries, big-endian dtypes, memory maps (modes "r" and "r+"), negative,
  Fortran and zero strides, nested lists of NumPy scalars, NumPy scalar types.
* Accepted or refused with a ValueError/TypeError that names the argument (the
  callable's class for an enum's value): np.matrix (always 2-D: a 1-D argument
  gets a row), objects with only __array__ / __array_interface__, object arrays
  of Python numbers, float16 and longdouble, array.array, memoryview, 0-d
  arrays, np.float32, Fraction and np.longdouble scalars.
* Refused (ValueError/TypeError): masked arrays or scalars with masked entries
  (NumPy's conversions read the data under the mask), complex dtypes and
  values even with zero imaginary parts, Decimal.
"""


class ArrayOnly:
    """An object NumPy reads only through ``__array__`` (NumPy 2's ``copy=`` protocol)."""

    def __init__(self, data: np.ndarray) -> None:
        self._data = data

    def __array__(self, dtype: Any = None, copy: bool | None = None) -> np.ndarray:
        if copy:
            return np.array(self._data, dtype=dtype, copy=True)
        return np.asarray(self._data, dtype=dtype)

    def __repr__(self) -> str:
        return f"ArrayOnly({self._data!r})"


class InterfaceOnly:
    """An object NumPy reads only through ``__array_interface__`` (a foreign buffer)."""

    def __init__(self, data: np.ndarray) -> None:
        self._data = data  # keeps the buffer alive
        self.__array_interface__ = data.__array_interface__

    def __repr__(self) -> str:
        return f"InterfaceOnly({self._data!r})"


@dataclass(frozen=True)
class Variant:
    """A foreign spelling of a valid value.

    ``make(valid, folder) -> (foreign, plain)`` or ``SKIP``; ``plain`` is the
    float64 C-contiguous array (or Python number) the foreign value stands for.
    """

    label: str
    make: Callable[[Any, Path], Any]
    expect: str = SAME
    layout: bool = False  # a layout or dtype numba would compile a new specialisation for
    may_refuse: bool = False  # a refusal naming the argument is an answer too (see POLICY)


def _numeric(v: Any) -> np.ndarray | None:
    """The valid value as an array, if it is a real (not boolean) array of values."""
    if isinstance(v, np.ndarray):
        arr = v
    elif isinstance(v, (list, tuple)) and v and not is_navkit_object(v):
        try:
            arr = np.asarray(v)
        except (TypeError, ValueError):
            return None
    else:
        return None
    if arr.ndim == 0 or arr.dtype.kind not in "biuf" or type(arr) is not np.ndarray:
        return None
    return arr


def _plain(a: np.ndarray) -> np.ndarray:
    return np.array(a, dtype=np.float64 if a.dtype.kind == "f" else a.dtype, order="C")


def _array_variant(label: str, fn: Callable[[np.ndarray, Path], Any], **kw: Any) -> Variant:
    def make(v: Any, folder: Path) -> Any:
        arr = _numeric(v)
        if arr is None:
            return SKIP
        out = fn(np.array(arr, copy=True), folder)
        if out is SKIP:
            return SKIP
        if isinstance(out, tuple) and len(out) == 2 and out[0] is PAIR:
            return out[1]
        return out, _plain(arr)

    return Variant(label, make, **kw)


PAIR = object()  # marks a (foreign, plain) pair returned by a variant function


def _mask_first(a: np.ndarray, _f: Path) -> Any:
    if a.size == 0:
        return SKIP
    mask = np.zeros(a.shape, dtype=bool)
    mask.flat[0] = True
    return np.ma.array(a, mask=mask)


def _matrix(a: np.ndarray, _f: Path) -> Any:
    if a.ndim > 2 or a.dtype.kind == "b":
        return SKIP
    # Always 2-D: a 1-D argument becomes a row, which must act as the plain 2-D
    # array of the same values (the same answer, or the same refusal).
    matrix = np.asmatrix(a)
    return PAIR, (matrix, np.array(matrix, dtype=_plain(a).dtype))


def _big_endian(a: np.ndarray, _f: Path) -> Any:
    if a.dtype.kind == "b":
        return SKIP
    return a.astype(a.dtype.newbyteorder(">"))


def _big_endian_as(code: str) -> Callable[[np.ndarray, Path], Any]:
    def fn(a: np.ndarray, _f: Path) -> Any:
        if a.dtype.kind not in "iub":
            return SKIP
        info = np.iinfo(np.dtype(code))
        if a.size and (a.min() < info.min or a.max() > info.max):
            return SKIP
        native = a.astype(np.dtype(code).newbyteorder("="))
        return PAIR, (a.astype(code), native)

    return fn


_MAPS: list[Any] = []  # memory maps stay open until the test module is done


def _memmap(mode: str) -> Callable[[np.ndarray, Path], Any]:
    def fn(a: np.ndarray, folder: Path) -> Any:
        if a.size == 0:
            return SKIP
        path = Path(tempfile.mkstemp(dir=folder, suffix=".bin")[1])
        a.tofile(path)
        out = np.memmap(path, dtype=a.dtype, mode=mode, shape=a.shape)
        _MAPS.append(out)
        return out

    return fn


def _reversed_view(a: np.ndarray, _f: Path) -> Any:
    if a.size < 2:
        return SKIP
    index = tuple(slice(None, None, -1) for _ in range(a.ndim))
    return a[index].copy()[index]


def _fortran(a: np.ndarray, _f: Path) -> Any:
    if a.ndim < 2 or a.shape[0] < 2 or a.shape[1] < 2:
        return SKIP
    return np.asfortranarray(a)


def _broadcast(a: np.ndarray, _f: Path) -> Any:
    if a.size < 2 or a.shape[0] < 2:
        return SKIP
    view = np.broadcast_to(a[:1], a.shape)
    plain = np.array(view, dtype=np.float64 if a.dtype.kind == "f" else a.dtype)
    return PAIR, (view, plain)


def _object_floats(a: np.ndarray, _f: Path) -> Any:
    if a.dtype.kind == "b":
        return SKIP
    out = np.empty(a.shape, dtype=object)
    for index, x in np.ndenumerate(a):
        out[index] = float(x) if a.dtype.kind == "f" else int(x)
    return out


def _float16(a: np.ndarray, _f: Path) -> Any:
    if a.dtype.kind != "f" or not np.all(np.abs(a[np.isfinite(a)]) < 6e4):
        return SKIP
    half = a.astype(np.float16)
    return PAIR, (half, half.astype(np.float64))


def _longdouble(a: np.ndarray, _f: Path) -> Any:
    if a.dtype.kind != "f":
        return SKIP
    return a.astype(np.longdouble)


def _complex(a: np.ndarray, _f: Path) -> Any:
    if a.dtype.kind == "b":
        return SKIP
    return a.astype(np.complex128)


def _numpy_scalars(a: np.ndarray, _f: Path) -> Any:
    def conv(x: Any) -> Any:
        if isinstance(x, np.ndarray) and x.ndim:
            return [conv(row) for row in x]
        return x[()] if isinstance(x, np.ndarray) else x

    return conv(a)


def _array_array(a: np.ndarray, _f: Path) -> Any:
    if a.ndim != 1 or a.dtype.kind not in "fiu":
        return SKIP
    return array.array("d" if a.dtype.kind == "f" else "q", a.tolist())


def _memoryview(a: np.ndarray, _f: Path) -> Any:
    return memoryview(np.ascontiguousarray(a))


def _memoryview_big(a: np.ndarray, _f: Path) -> Any:
    if a.dtype.kind == "b":
        return SKIP
    return memoryview(a.astype(a.dtype.newbyteorder(">")))


ARRAY_VARIANTS: list[Variant] = [
    _array_variant("masked, no entry masked", lambda a, _f: np.ma.array(a)),
    _array_variant(
        "masked, an all-False mask", lambda a, _f: np.ma.array(a, mask=np.zeros(a.shape, bool))
    ),
    _array_variant("masked, first entry masked", _mask_first, expect=REJECT),
    _array_variant("np.matrix", _matrix, may_refuse=True),
    _array_variant("big-endian", _big_endian, layout=True),
    _array_variant("big-endian >i4", _big_endian_as(">i4"), layout=True),
    _array_variant("big-endian >u1", _big_endian_as(">u1"), layout=True),
    _array_variant("np.memmap mode 'r'", _memmap("r"), layout=True),
    _array_variant("np.memmap mode 'r+'", _memmap("r+"), layout=True),
    _array_variant("negative strides", _reversed_view, layout=True),
    _array_variant("Fortran order", _fortran, layout=True),
    _array_variant("zero-stride broadcast view", _broadcast, layout=True),
    _array_variant("__array__ only", lambda a, _f: ArrayOnly(a), may_refuse=True),
    _array_variant("__array_interface__ only", lambda a, _f: InterfaceOnly(a), may_refuse=True),
    _array_variant("object dtype of Python numbers", _object_floats, may_refuse=True),
    _array_variant("float16", _float16, layout=True, may_refuse=True),
    _array_variant("longdouble", _longdouble, layout=True, may_refuse=True),
    _array_variant("complex dtype, zero imaginary parts", _complex, expect=REJECT),
    _array_variant("nested lists of NumPy scalars", _numpy_scalars),
    _array_variant("array.array", _array_array, may_refuse=True),
    _array_variant("memoryview", _memoryview, may_refuse=True),
    _array_variant("memoryview of big-endian data", _memoryview_big, layout=True, may_refuse=True),
]


def _real_scalar(v: Any) -> float | int | None:
    """The valid value as a finite Python number, if it is one."""
    if isinstance(v, (bool, np.bool_)) or not isinstance(v, (int, float, np.integer, np.floating)):
        return None
    x = v.item() if isinstance(v, np.generic) else v
    return x if isinstance(x, int) or math.isfinite(x) else None


def _scalar_variant(label: str, fn: Callable[[Any], Any], **kw: Any) -> Variant:
    kw.setdefault("may_refuse", label != "numpy scalar")

    def make(v: Any, _folder: Path) -> Any:
        x = _real_scalar(v)
        if x is None:
            return SKIP
        out = fn(x)
        if out is SKIP:
            return SKIP
        if isinstance(out, tuple) and len(out) == 2 and out[0] is PAIR:
            return out[1]
        return out, x

    return Variant(label, make, **kw)


def _float32(x: Any) -> Any:
    if isinstance(x, int):
        return SKIP
    single = np.float32(x)
    return PAIR, (single, float(single))


SCALAR_VARIANTS: list[Variant] = [
    _scalar_variant("numpy scalar", lambda x: np.int64(x) if isinstance(x, int) else np.float64(x)),
    _scalar_variant("np.float32 scalar", _float32),
    _scalar_variant("0-d array", lambda x: SKIP if isinstance(x, int) else np.array(x)),
    _scalar_variant(
        "0-d big-endian array",
        lambda x: np.array(x, dtype=">i8" if isinstance(x, int) else ">f8"),
    ),
    _scalar_variant("0-d masked array, unmasked", lambda x: np.ma.array(x)),
    _scalar_variant("0-d masked array, masked", lambda x: np.ma.array(x, mask=True), expect=REJECT),
    _scalar_variant("Fraction", lambda x: SKIP if isinstance(x, int) else fractions.Fraction(x)),
    _scalar_variant("Decimal", lambda x: decimal.Decimal(x), expect=REJECT),
    _scalar_variant("np.longdouble", lambda x: SKIP if isinstance(x, int) else np.longdouble(x)),
    _scalar_variant(
        "complex with zero imaginary part",
        lambda x: np.complex128(x),
        expect=REJECT,
    ),
]

FLAG_VARIANTS: list[Variant] = [
    Variant(
        "np.bool_",
        lambda v, _f: (np.bool_(v), bool(v)) if isinstance(v, bool) else SKIP,
    ),
]


def variants_for(kind: Any) -> list[Variant]:
    if isinstance(kind, Flag):
        return FLAG_VARIANTS
    if isinstance(kind, Real):
        return SCALAR_VARIANTS
    if isinstance(kind, (Array, PoseLike, Cell)):
        return ARRAY_VARIANTS
    return []


# --------------------------------------------------------------------------- running


def _dispatchers() -> list[Any]:
    from numba.core.dispatcher import Dispatcher

    out = []
    for name, module in list(sys.modules.items()):
        if not name.startswith("navkit.") or module is None:
            continue
        for value in list(vars(module).values()):
            if isinstance(value, Dispatcher) and value.py_func.__module__ == name:
                out.append(value)
    return out


def kernel_signatures() -> dict[str, int]:
    """``{"module.kernel": number of compiled signatures}`` of the loaded navkit kernels."""
    return {
        f"{d.py_func.__module__}.{d.py_func.__name__}": len(d.signatures) for d in _dispatchers()
    }


def _normalise(snap: Any) -> Any:
    """A snapshot where opaque objects compare by type, not identity."""
    if isinstance(snap, tuple) and len(snap) == 2 and snap[0] == "id":
        return ("opaque",)
    if isinstance(snap, Path):  # each call writes into a folder of its own
        return ("path", snap.name)
    if isinstance(snap, tuple) and snap and snap[0] == "ndarray":
        return snap
    if isinstance(snap, tuple) and len(snap) == 2 and _wall_clock(snap[0]):
        return (snap[0], ("wall-clock time",))  # a (name, value) pair of a record
    if isinstance(snap, tuple):
        return tuple(_normalise(s) for s in snap)
    if isinstance(snap, list):
        return [_normalise(s) for s in snap]
    if isinstance(snap, dict):
        return {
            k: ("wall-clock time",) if _wall_clock(k) else _normalise(s) for k, s in snap.items()
        }
    return snap


def _wall_clock(name: object) -> bool:
    """Times measured in results (``wall_time``, ``plan_wall_time``, a warm-up's
    ``seconds`` and ``cpu_seconds``) differ run to run."""
    return isinstance(name, str) and ("wall_time" in name or name in ("seconds", "cpu_seconds"))


def _arrays_in(value: Any, depth: int = 0) -> Iterator[np.ndarray]:
    if depth > 4:
        return
    if isinstance(value, np.ndarray):
        yield value
    elif isinstance(value, (list, tuple)):
        for v in value[:50]:
            yield from _arrays_in(v, depth + 1)
    elif isinstance(value, dict):
        for v in list(value.values())[:50]:
            yield from _arrays_in(v, depth + 1)
    elif is_navkit_object(value):
        for _name, v in public_state(value):
            yield from _arrays_in(v, depth + 1)


@dataclass
class Outcome:
    result: Any = None  # normalised snapshot of (result, receiver)
    error: BaseException | None = None
    raw: Any = None


def _invoke(s: Spec, path: tuple[str, ...] | None, value: Any, folder: Path) -> Outcome:
    tree = s.make(Ctx(folder))
    if path is not None:
        replace(tree, path, value)
    built: list[tuple[str, Any]] = []
    with np.errstate(all="ignore"), memory_limit(), watchdog(60.0):
        try:
            receiver = None
            if tree.method is not None:
                receiver = materialize(tree.target, built, "self.")
                if tree.prepare is not None:
                    tree.prepare(receiver)
            args = {k: materialize(v, built, f"{k}.") for k, v in tree.arguments.items()}
            result = tree.invoke(receiver, args)
        except (KeyboardInterrupt, SystemExit):
            raise
        except BaseException as exc:
            return Outcome(error=exc)
    raw = (result, receiver)
    return Outcome(result=_normalise(snapshot(raw)), raw=raw)


def first_difference(a: Any, b: Any, where: str = "") -> str | None:
    """Where two normalised snapshots first differ (``None`` when they are the same)."""
    if same(a, b):
        return None
    if type(a) is type(b) and isinstance(a, (tuple, list)) and len(a) == len(b):
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            if isinstance(x, tuple) and len(x) == 2 and isinstance(x[0], str):
                label = f"{where}.{x[0]}"
            else:
                label = f"{where}[{i}]"
            found = first_difference(x, y, label)
            if found is not None:
                return found
    if type(a) is dict and type(b) is dict and a.keys() == b.keys():
        for k in a:
            found = first_difference(a[k], b[k], f"{where}[{k!r}]")
            if found is not None:
                return found
    return f"{where or 'the result'}: {_short(a)} != {_short(b)}"


def _short(value: Any) -> str:
    text = " ".join(repr(value).split())
    return text if len(text) <= 120 else text[:119] + "…"


def _input_state(value: Any) -> Any:
    if isinstance(value, np.memmap):
        return ("memmap", bytes(Path(value.filename).read_bytes()), np.array(value))
    if isinstance(value, np.ma.MaskedArray):
        return ("masked", np.array(value.data), np.ma.getmaskarray(value).copy())
    if isinstance(value, (ArrayOnly, InterfaceOnly)):
        return ("wrapped", np.array(value._data))
    if isinstance(value, np.ndarray):
        return ("ndarray", np.array(value), value.strides, bool(value.flags.writeable))
    if isinstance(value, memoryview):
        return ("memoryview", value.tobytes())
    if isinstance(value, array.array):
        return ("array.array", value.tolist())
    return ("other", repr(value))


def _states_equal(a: Any, b: Any) -> bool:
    if a[0] != b[0] or len(a) != len(b):
        return False
    for x, y in zip(a[1:], b[1:], strict=True):
        if isinstance(x, np.ndarray):
            if x.shape != y.shape or x.dtype != y.dtype:
                return False
            if x.dtype.kind == "O":
                pairs = zip(x.ravel().tolist(), y.ravel().tolist(), strict=True)
                if not all(a is b or a == b or (a != a and b != b) for a, b in pairs):
                    return False
            elif not np.array_equal(x, y, equal_nan=x.dtype.kind in "fc"):
                return False
        elif x != y:
            return False
    return True


def _buffer_of(value: Any) -> np.ndarray | None:
    if isinstance(value, (ArrayOnly, InterfaceOnly)):
        return value._data
    if isinstance(value, np.ndarray):
        return value
    if isinstance(value, memoryview):
        with contextlib.suppress(Exception):
            return np.asarray(value)
    return None


ALLOWED = (ValueError, TypeError, NavkitError)


def names_the_argument(err: BaseException, spec_name: str, path: tuple[str, ...]) -> bool:
    """Whether a refusal's message names the argument (or, for an enum, its class)."""
    text = str(err)
    return path[-1] in text or spec_name.rsplit(".", 1)[-1] in text


def check_variant(
    s: Spec, path: tuple[str, ...], valid: Any, variant: Variant, folder: Path
) -> list[str]:
    """What went wrong when the argument at ``path`` is given as ``variant``."""
    made = variant.make(valid, folder)
    if made is SKIP:
        return []
    foreign, plain = made
    problems: list[str] = []
    where = f"{s.name}: {'.'.join(path)} = {variant.label}"
    plain_out = _invoke(s, path, plain, folder)
    before = kernel_signatures()
    state_before = _input_state(foreign)
    out = _invoke(s, path, foreign, folder)
    after = kernel_signatures()
    grown = sorted(k for k, n in after.items() if n > before.get(k, 0))
    if grown and variant.layout:
        problems.append(f"{where}: compiled new kernel specialisations {grown}")
    if not _states_equal(state_before, _input_state(foreign)):
        problems.append(f"{where}: modified the caller's input")
    err = out.error
    if err is not None and isinstance(err, Hang):
        return [*problems, f"{where}: hangs"]
    if err is not None and not isinstance(err, ALLOWED):
        return [*problems, f"{where}: {type(err).__module__}.{type(err).__name__}: {err}"]
    if variant.expect == REJECT:
        if err is None and plain_out.error is None:
            problems.append(f"{where}: accepted (a value that must be refused)")
        return problems
    if err is None and plain_out.error is not None:
        problems.append(
            f"{where}: accepted, but the plain value is refused: "
            f"{type(plain_out.error).__name__}: {plain_out.error}"
        )
        return problems
    if err is not None and plain_out.error is None:
        if not (variant.may_refuse and names_the_argument(err, s.name, path)):
            problems.append(f"{where}: refused: {type(err).__name__}: {err}")
        return problems
    if err is not None and plain_out.error is not None:
        if type(err) is not type(plain_out.error):
            problems.append(
                f"{where}: {type(err).__name__}: {err} where the plain value gives "
                f"{type(plain_out.error).__name__}: {plain_out.error}"
            )
        return problems
    difference = first_difference(out.result, plain_out.result)
    if difference is not None:
        problems.append(f"{where}: a different answer than the plain value ({difference})")
    buffer = _buffer_of(foreign)
    if buffer is not None and buffer.size:
        for arr in _arrays_in(out.raw):
            if np.shares_memory(arr, buffer):
                problems.append(f"{where}: the result shares memory with the caller's buffer")
                break
    return problems


def check_spec(
    name: str, folder: Path, *, only: Callable[[Variant], bool] | None = None
) -> list[str]:
    """Every variant of every argument of spec ``name``: the problems found."""
    s = SPECS[name]
    tree = s.make(Ctx(folder))
    problems: list[str] = []
    base = _invoke(s, None, None, folder)
    if base.error is not None:
        return []  # specs that expect an error (abstract classes) have no answer to compare
    for slot, kind, value, _nested in slots(tree):
        for variant in variants_for(kind):
            if only is not None and not only(variant):
                continue
            problems += check_variant(s, slot.path, value, variant, folder)
    return problems


def close_maps() -> None:
    for m in _MAPS:
        mm = getattr(m, "_mmap", None)
        if mm is not None:
            with contextlib.suppress(Exception):
                mm.close()
    _MAPS.clear()
