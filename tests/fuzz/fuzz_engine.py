"""The machinery of the public-API fuzz test: calls, argument kinds, hostile values, checks.

A *spec* (see ``fuzz_specs.py``) describes one valid call of a public callable as
a tree of :class:`Call` objects (a method call's receiver and any navkit object
argument may themselves be lazy calls). The engine replaces one argument
anywhere in the tree by a hostile value and checks navkit's promise:

* only ``ValueError``, ``TypeError`` or a ``navkit.errors.NavkitError`` subclass is
  raised (a file reader may also raise ``FileNotFoundError`` for a missing
  file) — never another type, a hang or a ``MemoryError``;
* a value that is plainly wrong for the argument's *kind* (None for a required
  argument, a string for a number, a complex number, NaN where the kind wants a
  finite value, an object of the wrong navkit type...) is rejected;
* an equivalent spelling of the valid value (a list, a tuple, a read-only or
  non-contiguous array) is accepted;
* no NaN in the output (or in the receiver's state afterwards) when no input
  holds NaN, and no infinity unless an input holds one or the spec documents it;
* inputs are never modified; a failed call leaves the receiver's public state and
  the files in its folder as they were; a stateful object stays usable.

Each call runs under a watchdog (``CALL_TIMEOUT_S`` of CPU time, or ``WALL_TIMEOUT_S``
of wall-clock time for a call that waits: a hang is a failure) and an address-space
limit (``MEMORY_HEADROOM`` above the process's size), so a missing size check shows as
a ``MemoryError`` failure instead of exhausting the machine.
"""

from __future__ import annotations

import contextlib
import enum
import gc
import inspect
import math
import numbers
import os
import pkgutil
import resource
import shutil
import signal
import sys
import tempfile
import threading
import time
import types
import warnings
import weakref
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

import navkit
from navkit.errors import FilterError, NavkitError
from navkit.sim._scenario import _MAX_TRIALS

SRC = Path(navkit.__file__).resolve().parent
#: A call's bound in CPU time (s) before it counts as hanging (see :func:`watchdog`).
CALL_TIMEOUT_S = 10.0
#: A call's bound in wall-clock time (s), for one blocked without computing: far
#: above ``CALL_TIMEOUT_S``, as 10 s of CPU take 70 s with 14 processes on 2 cores.
WALL_TIMEOUT_S = 120.0
#: The bound while numba compiles or loads a kernel inside a call (s): its compile
#: time is not the call's (see :func:`watchdog`).
COMPILE_TIMEOUT_S = 600.0
MEMORY_HEADROOM = 3 << 30  # address space allowed on top of the process's current size


# --------------------------------------------------------------------------- discovery


def public_modules() -> list[str]:
    """Every public (sub)package and module of navkit: no part of its name starts with '_'."""
    names = ["navkit"]
    for info in pkgutil.walk_packages([str(SRC)], prefix="navkit."):
        if not any(part.startswith("_") for part in info.name.split(".")):
            names.append(info.name)
    return sorted(names)


def _public_methods(cls: type) -> list[str]:
    """Methods a user can call on ``cls`` or its instances, defined by navkit classes.

    Public names plus the operators navkit defines (``__call__``, ``__add__``, ...);
    methods inherited from builtins or the standard library (``int.bit_length``,
    ``Exception.with_traceback``) are not navkit's.
    """
    out = []
    for name in dir(cls):
        if name.startswith("_") and name not in OPERATORS:
            continue
        owner = next((k for k in cls.__mro__ if name in vars(k)), None)
        if owner is None or not owner.__module__.startswith("navkit"):
            continue
        raw = vars(owner)[name]
        if isinstance(raw, (staticmethod, classmethod)) or inspect.isfunction(raw):
            out.append(name)
    return sorted(out)


OPERATORS = ("__call__", "__add__", "__radd__", "__matmul__", "__rmatmul__", "__getitem__")


@dataclass(frozen=True)
class PublicCallable:
    name: str  # canonical public name, e.g. "navkit.geometry.Pose2D.compose"
    obj: Any  # the function, class or (for methods) the class
    method: str | None = None
    abstract: bool = False  # a method of an abstract class or protocol


def _canonical_names() -> dict[int, str]:
    """``id(obj) -> name`` for every public object: the deepest exporting package."""
    names: dict[int, str] = {}
    depth: dict[int, int] = {}
    for module_name in public_modules():
        module = __import__(module_name, fromlist=["__all__"])
        for attr in getattr(module, "__all__", []):
            obj = getattr(module, attr)
            d = module_name.count(".")
            # The deepest package whose name prefixes the object's own module wins.
            home = getattr(obj, "__module__", "") or ""
            rank = d + (100 if home.startswith(module_name) else 0)
            if id(obj) not in names or rank > depth[id(obj)]:
                names[id(obj)] = f"{module_name}.{attr}"
                depth[id(obj)] = rank
    return names


CANONICAL = _canonical_names()


def _is_abstract(cls: type) -> bool:
    return inspect.isabstract(cls) or bool(getattr(cls, "_is_protocol", False))


def public_callables() -> list[PublicCallable]:
    """Every public callable: functions, classes (their constructors) and their methods."""
    out: list[PublicCallable] = []
    seen: set[int] = set()
    for module_name in public_modules():
        module = __import__(module_name, fromlist=["__all__"])
        for attr in getattr(module, "__all__", []):
            obj = getattr(module, attr)
            if id(obj) in seen or not callable(obj):
                continue
            seen.add(id(obj))
            name = CANONICAL[id(obj)]
            out.append(PublicCallable(name, obj))
            if inspect.isclass(obj):
                abstract = _is_abstract(obj)
                out.extend(
                    PublicCallable(f"{name}.{m}", obj, m, abstract) for m in _public_methods(obj)
                )
    return out


def area_of(name: str) -> str:
    """The engineer's area a public name belongs to (for the findings list)."""
    parts = name.split(".")
    sub = parts[1] if len(parts) > 2 else "navkit"
    if sub in ("mapping",):
        return "mapping"
    if sub == "planning":
        return "planning"
    if sub in ("geometry", "kinematics", "estimation", "control", "behaviours"):
        return sub
    return "errors/top-level"


# --------------------------------------------------------------------------- calls


class Call:
    """A lazy call: ``target(*args, **kwargs)`` or ``receiver.method(*args, **kwargs)``.

    ``receiver`` (for a method) and any argument may themselves be ``Call``
    objects, built just before the outer call. ``prepare`` runs on the built
    receiver before the method (e.g. plan once before ``replan``).
    """

    def __init__(
        self,
        target: Any,
        args: tuple[Any, ...],
        kwargs: dict[str, Any],
        *,
        method: str | None = None,
        prepare: Callable[[Any], Any] | None = None,
    ) -> None:
        self.target = target  # a callable, or the receiver (Call or object) when method is set
        self.method = method
        self.prepare = prepare
        self.signature = _signature(self._callable_for_signature())
        if self.signature is not None and method is not None:
            raw = inspect.getattr_static(self.receiver_class(), method)
            if not isinstance(raw, (classmethod, staticmethod)):
                params = list(self.signature.parameters.values())[1:]  # self
                self.signature = self.signature.replace(parameters=params)
        self._raw: tuple[tuple[Any, ...], dict[str, Any]] | None = None
        if self.signature is None:
            self.arguments: dict[str, Any] = {}
            self._raw = (args, kwargs)
        else:
            self.arguments = dict(self.signature.bind_partial(*args, **kwargs).arguments)

    # The class of the receiver (for a method call) without building it.
    def receiver_class(self) -> type:
        target = self.target
        if isinstance(target, Call):
            return target.result_class()
        return type(target)

    def result_class(self) -> type:
        """The class of what this call returns (known for constructors and classmethods)."""
        if self.method is None:
            if inspect.isclass(self.target):
                return self.target
            owner = getattr(self.target, "__self__", None)
            if inspect.isclass(owner):
                return owner
        return type(materialize(self.copy(), []))

    def _callable_for_signature(self) -> Any:
        if self.method is None:
            return self.target
        return getattr(self.receiver_class(), self.method)

    @property
    def key(self) -> str | None:
        """The canonical public name of the called function, class or method."""
        if self.method is not None:
            cls = self.receiver_class()
            owner = CANONICAL.get(id(cls))
            return f"{owner}.{self.method}" if owner else None
        owner_cls = getattr(self.target, "__self__", None)
        if inspect.isclass(owner_cls) and id(owner_cls) in CANONICAL:
            return f"{CANONICAL[id(owner_cls)]}.{self.target.__name__}"
        return CANONICAL.get(id(self.target))

    def parameters(self) -> list[inspect.Parameter]:
        if self.signature is None:
            return []
        return [
            p
            for p in self.signature.parameters.values()
            if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)
        ]

    def value_of(self, param: inspect.Parameter) -> Any:
        return self.arguments.get(param.name, param.default)

    def copy(self) -> Call:
        """A shallow structural copy (nested calls copied, leaf values shared)."""
        new = object.__new__(Call)
        new.__dict__.update(self.__dict__)
        new.arguments = {
            k: v.copy() if isinstance(v, Call) else v for k, v in self.arguments.items()
        }
        if isinstance(self.target, Call):
            new.target = self.target.copy()
        return new

    def invoke(self, receiver: Any, arguments: dict[str, Any]) -> Any:
        fn = self.target if self.method is None else getattr(receiver, self.method)
        if self.signature is None:
            assert self._raw is not None
            return fn(*self._raw[0], **self._raw[1])
        bound = inspect.BoundArguments(self.signature, dict(arguments))  # type: ignore[arg-type]
        return fn(*bound.args, **bound.kwargs)

    def render(self, depth: int = 0) -> str:
        """Python-like text of the call, for failure reports."""
        if self._raw is not None:
            parts = [short(a) for a in self._raw[0]]
            parts += [f"{k}={short(v)}" for k, v in self._raw[1].items()]
        else:
            parts = []
            positional = True
            for p in self.parameters():
                if p.name not in self.arguments:
                    positional = False
                    continue
                text = _render_value(self.arguments[p.name], depth)
                if positional and p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD):
                    parts.append(text)
                else:
                    parts.append(f"{p.name}={text}")
        inner = ", ".join(parts)
        if self.method is not None:
            return f"{_render_value(self.target, depth)}.{self.method}({inner})"
        return f"{_qualname(self.target)}({inner})"


def _render_value(value: Any, depth: int) -> str:
    if isinstance(value, Call):
        return value.render(depth + 1)
    if isinstance(value, (list, tuple)) and any(isinstance(v, Call) for v in value):
        inner = ", ".join(_render_value(v, depth) for v in value)
        return (
            f"[{inner}]"
            if isinstance(value, list)
            else f"({inner}{',' if len(value) == 1 else ''})"
        )
    return short(value)


def _qualname(obj: Any) -> str:
    owner = getattr(obj, "__self__", None)
    if inspect.isclass(owner):
        return f"{owner.__name__}.{obj.__name__}"
    return getattr(obj, "__qualname__", getattr(obj, "__name__", repr(obj)))


_SIGNATURES: dict[tuple[Any, Any], inspect.Signature | None] = {}


def _signature(obj: Any) -> inspect.Signature | None:
    key = (getattr(obj, "__func__", obj), getattr(obj, "__self__", None))
    try:
        return _SIGNATURES[key]
    except (KeyError, TypeError):
        pass
    try:
        sig: inspect.Signature | None = inspect.signature(obj)
    except (TypeError, ValueError):
        sig = None
    with contextlib.suppress(TypeError):
        _SIGNATURES[key] = sig
    return sig


def call(target: Any, /, *args: Any, **kwargs: Any) -> Call:
    """A lazy call of a function, class or classmethod."""
    return Call(target, args, kwargs)


def method(receiver: Any, name: str, /, *args: Any, prepare: Any = None, **kwargs: Any) -> Call:
    """A lazy method call on ``receiver`` (a :class:`Call` building it, or an object)."""
    return Call(receiver, args, kwargs, method=name, prepare=prepare)


def materialize(value: Any, built: list[tuple[str, Any]], path: str = "") -> Any:
    """Build every nested call in ``value``; built objects are appended to ``built``."""
    if isinstance(value, Call):
        receiver = None
        if value.method is not None:
            receiver = materialize(value.target, built, f"{path}self.")
            if value.prepare is not None:
                value.prepare(receiver)
        args = {k: materialize(v, built, f"{path}{k}.") for k, v in value.arguments.items()}
        try:
            out = value.invoke(receiver, args)
        except Exception as exc:
            _mark_raised_at(exc, path)
            raise
        built.append((path.rstrip(".") or "<result>", out))
        return out
    if isinstance(value, list) and any(isinstance(v, Call) for v in value):
        return [materialize(v, built, f"{path}{i}.") for i, v in enumerate(value)]
    if isinstance(value, tuple) and any(isinstance(v, Call) for v in value):
        return tuple(materialize(v, built, f"{path}{i}.") for i, v in enumerate(value))
    return value


RAISED_AT = "_navkit_fuzz_raised_at"
"""The attribute :func:`materialize` puts on an exception raised by a nested call."""


def _mark_raised_at(exc: BaseException, path: str) -> None:
    """Note which nested call refused (the innermost one: set only once, on the way out).

    ``raised_at(exc)`` then tells a check on the message which call's parameter
    names the caller wrote for it (``test_review8_messages.py``).
    """
    if not hasattr(exc, RAISED_AT):
        with contextlib.suppress(AttributeError, TypeError):
            setattr(exc, RAISED_AT, tuple(p for p in path.split(".") if p))


def raised_at(exc: BaseException) -> tuple[str, ...]:
    """The path of the nested call that raised ``exc`` (``()``: the outer call itself)."""
    return tuple(getattr(exc, RAISED_AT, ()))


# --------------------------------------------------------------------------- value tags


_NAVKIT_TYPES: dict[type, bool] = {}


def is_navkit_object(value: Any) -> bool:
    t = type(value)
    known = _NAVKIT_TYPES.get(t)
    if known is None:
        known = _NAVKIT_TYPES[t] = t.__module__.startswith("navkit") and not issubclass(
            t, enum.Enum
        )
    return known


def tags_of(value: Any) -> set[str]:
    """What a value is, as far as the contract cares (see ``Kind.must_reject``)."""
    if value is None:
        return {"none"}
    if isinstance(value, (bool, np.bool_)):
        return {"bool"}
    if isinstance(value, (str, bytes)):
        return {"str"}
    if isinstance(value, (complex, np.complexfloating)):
        return {"complex", "scalar"}
    if isinstance(value, numbers.Integral):
        return {"int", "scalar"} | ({"overflow"} if abs(int(value)) > 1.7e308 else set())
    if isinstance(value, numbers.Real):
        f = float(value)
        out = {"real", "scalar"}
        if math.isnan(f):
            out.add("nan")
        elif math.isinf(f):
            out.add("posinf" if f > 0 else "neginf")
        elif not f.is_integer():
            out.add("fraction")
        return out
    if isinstance(value, Mapping):
        return {"mapping"}
    if isinstance(value, Path | os.PathLike):
        return {"path"}
    if is_navkit_object(value):
        return {"navkit"}
    if isinstance(value, np.ndarray):
        return _array_tags(value) | ({"sequence"} if value.ndim else {"scalar"})
    if isinstance(value, (list, tuple)):
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                arr = np.array(value, dtype=object)
        except (ValueError, TypeError):
            return {"sequence", "ragged"}
        if arr.ndim == 0:
            return {"sequence"}
        if (
            arr.size
            and arr.dtype == object
            and any(isinstance(v, (list, tuple)) for v in arr.ravel())
        ):
            return {"sequence", "ragged"}
        return _object_elements(arr) | {"sequence"}
    if callable(value):
        return {"callable"}
    return {"opaque"}


def _array_tags(arr: np.ndarray) -> set[str]:
    kind = arr.dtype.kind
    if kind == "b":
        return {"bool_array"}
    if kind == "c":
        return {"complex"}
    if kind in "US":
        return {"str"}
    if kind in "mMV":
        return {"nonnumeric"}
    if kind == "O":
        return _object_elements(arr)
    out: set[str] = set()
    if kind == "f" and arr.size:
        if np.isnan(arr).any():
            out.add("nan")
        if np.isposinf(arr).any():
            out.add("posinf")
        if np.isneginf(arr).any():
            out.add("neginf")
        finite = arr[np.isfinite(arr)]
        if finite.size and not np.all(finite == np.floor(finite)):
            out.add("fraction")
    if arr.size == 0:
        out.add("empty")
    return out


def _object_elements(arr: np.ndarray) -> set[str]:
    out: set[str] = set()
    if arr.size == 0:
        out.add("empty")
    for item in arr.ravel()[:1000]:
        t = tags_of(item)
        if t & {"none", "str", "mapping", "opaque", "navkit", "callable", "complex", "ragged"}:
            out |= {"nonnumeric"} | (t & {"str", "complex", "none"})
        if "bool" in t:
            out.add("bool_array")
        out |= t & {"nan", "posinf", "neginf", "overflow", "fraction"}
    return out


# --------------------------------------------------------------------------- hostile values


class Ctx:
    """Per-case context: ``tmp``, a fresh folder for files (created when first used)."""

    def __init__(self, root: Path) -> None:
        self._root = root
        self._tmp: Path | None = None

    @property
    def tmp(self) -> Path:
        if self._tmp is None:
            self._tmp = Path(tempfile.mkdtemp(dir=self._root))
        return self._tmp

    @property
    def used(self) -> bool:
        return self._tmp is not None


@dataclass(frozen=True)
class Hostile:
    """A hostile replacement for an argument, derived from its valid value."""

    label: str
    make: Callable[[Any, Ctx], Any]
    equivalent: bool = False  # an equivalent spelling of the valid value: must be accepted
    extreme: bool = False  # a finite extreme value: also tried on arguments of nested calls
    tags: frozenset[str] = frozenset()  # extra tags (a callable that returns NaN...)
    must_reject: bool = False  # the kind says this value is wrong, whatever its tags


def h(label: str, value: Any, **kw: Any) -> Hostile:
    """A hostile constant (copied per case when mutable)."""
    if isinstance(value, np.ndarray):
        return Hostile(label, lambda _v, _c, a=value: a.copy(), **kw)
    return Hostile(label, lambda _v, _c, x=value: x, **kw)


def _wrong_objects() -> list[Hostile]:
    from navkit.geometry import Pose2D, Twist2D
    from navkit.kinematics import DiffDrive
    from navkit.mapping import LaserScan, OccupancyGrid

    return [
        Hostile("a Pose2D", lambda _v, _c: Pose2D(1.0, 2.0, 0.5)),
        Hostile("a Twist2D", lambda _v, _c: Twist2D(0.5, 0.0, 0.1)),
        Hostile(
            "an OccupancyGrid",
            lambda _v, _c: OccupancyGrid.from_occupancy(np.eye(3, dtype=bool), resolution=0.1),
        ),
        Hostile(
            "a LaserScan",
            lambda _v, _c: LaserScan(
                [1.0, 2.0], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0
            ),
        ),
        Hostile("a DiffDrive", lambda _v, _c: DiffDrive(track=0.3, wheel_radius=0.05)),
    ]


GARBAGE: list[Hostile] = [
    h("None", None),
    h("'abc'", "abc"),
    h("b'1'", b"1"),
    h("{}", {}),
    h("object()", object()),
    h("1+1j", 1 + 1j),
    h("np.complex128(1+0j)", np.complex128(1 + 0j)),
]


def _scalar_hostiles(integer: bool) -> list[Hostile]:
    out = [
        h("nan", math.nan),
        h("inf", math.inf),
        h("-inf", -math.inf),
        h("np.float32('nan')", np.float32("nan")),
        h("1e308", 1e308, extreme=True),
        h("-1e308", -1e308, extreme=True),
        h("5e-324", 5e-324, extreme=True),
        h("1e-300", 1e-300, extreme=True),
        h("0", 0, extreme=True),
        h("-0.0", -0.0),
        h("-1", -1, extreme=True),
        h("10**400 (a huge int)", 10**400, extreme=True),
        h("2**64", 2**64),
        h("-(2**63)", -(2**63)),
        h("True", True),
        h("'1.0'", "1.0"),
        h("[1.0]", [1.0]),
        h("np.array([1.0, 2.0])", np.array([1.0, 2.0])),
        h("np.float32(3.4e38)", np.float32(3.4e38)),
        Hostile("np.float64(valid)", lambda v, _c: _np_scalar(v), equivalent=True),
        Hostile("0-d array of valid", lambda v, _c: _zero_d(v), equivalent=True),
    ]
    if integer:
        out += [h("1.5", 1.5), h("2.0", 2.0), h("np.int8(-1)", np.int8(-1)), h("10**30", 10**30)]
    return out + GARBAGE


def _np_scalar(v: Any) -> Any:
    if isinstance(v, (bool, np.bool_)) or not isinstance(v, numbers.Real):
        return SKIP
    return np.int64(v) if isinstance(v, numbers.Integral) else np.float64(v)


def _zero_d(v: Any) -> Any:
    if isinstance(v, (bool, np.bool_, numbers.Integral)) or not isinstance(v, numbers.Real):
        return SKIP  # a 0-d array is a real number, not necessarily an integer
    return np.array(v)


def _as_array(v: Any) -> np.ndarray | None:
    if isinstance(v, np.ndarray):
        return v
    if isinstance(v, (list, tuple)):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                arr = np.asarray(v)
            except (ValueError, TypeError):
                return None
        if arr.dtype.kind in "biuf":
            return arr
    return None


SKIP = object()
"""Returned by a hostile's ``make`` when it does not apply to the valid value."""


def _derived(label: str, fn: Callable[[np.ndarray], Any], **kw: Any) -> Hostile:
    def make(v: Any, _c: Ctx) -> Any:
        arr = _as_array(v)
        if arr is None or arr.ndim == 0:
            if kw.get("equivalent"):
                return SKIP  # no array spelling of a scalar or None is equivalent to it
            arr = np.array([1.0, 2.0])
        with np.errstate(all="ignore"):
            return fn(np.array(arr, copy=True))

    return Hostile(label, make, **kw)


def _readonly(a: np.ndarray) -> np.ndarray:
    a.flags.writeable = False
    return a


def _strided(a: np.ndarray) -> np.ndarray:
    """The same values in a non-contiguous view."""
    return np.stack([a, a], axis=-1)[..., 0]


def _with_first(a: np.ndarray, value: Any) -> np.ndarray:
    if a.size == 0:
        return np.array([value])
    out = a.astype(np.result_type(a.dtype, np.asarray(value).dtype), copy=True)
    out.flat[0] = value
    return out


def _to_tuple(a: np.ndarray) -> Any:
    def conv(x: Any) -> Any:
        return tuple(conv(i) for i in x) if isinstance(x, list) else x

    return conv(a.tolist())


def array_hostiles(boolean: bool = False) -> list[Hostile]:
    """Hostile replacements for an array argument, derived from its valid value."""
    out = [
        _derived("the same as a list", lambda a: a.tolist(), equivalent=True),
        _derived("the same as a tuple", _to_tuple, equivalent=True),
        _derived("the same, read-only", _readonly, equivalent=True),
        _derived("the same, non-contiguous", _strided, equivalent=True),
        _derived(
            "the same in Fortran order",
            lambda a: np.asfortranarray(a) if a.ndim > 1 else SKIP,
            equivalent=True,
        ),
        _derived("as complex", lambda a: a.astype(complex)),
        _derived("as str dtype", lambda a: a.astype(str)),
        _derived("as object dtype", lambda a: a.astype(object)),
        _derived("object dtype with None", lambda a: _with_first(a.astype(object), None)),
        _derived("object dtype with a str", lambda a: _with_first(a.astype(object), "1.0")),
        _derived("as float32", lambda a: a.astype(np.float32)),
        _derived("as int8", lambda a: a.astype(np.int8)),
        _derived("as datetime64", lambda a: np.zeros(a.shape, dtype="datetime64[s]")),
        _derived("empty, same trailing shape", lambda a: np.empty((0, *a.shape[1:]), a.dtype)),
        _derived("empty 1-D", lambda a: np.array([], dtype=a.dtype), extreme=True),
        _derived("empty (0, 0)", lambda a: np.empty((0, 0), dtype=a.dtype)),
        _derived("one more axis in front", lambda a: a[None]),
        _derived("one more axis at the end", lambda a: a[..., None]),
        _derived("flattened", lambda a: a.ravel() if a.ndim > 1 else SKIP),
        _derived("transposed", lambda a: a.T if a.ndim > 1 and a.shape[0] != a.shape[1] else SKIP),
        _derived(
            "one more column",
            lambda a: (
                np.concatenate([a, a[..., :1]], axis=-1) if a.ndim and a.shape[-1] else a[None]
            ),
        ),
        _derived("first row only", lambda a: a[:1]),
        _derived(
            "first element as a 0-d array",
            lambda a: a.ravel()[:1].reshape(()) if a.size else np.array(1.0),
        ),
        _derived("ragged list", lambda a: [[1.0, 2.0], [3.0]]),
        h("3-D zeros (2, 2, 2)", np.zeros((2, 2, 2))),
    ]
    if not boolean:
        out += [
            _derived("as bool", lambda a: a.astype(bool)),
            _derived("NaN in the first element", lambda a: _with_first(a.astype(float), math.nan)),
            _derived("+inf in the first element", lambda a: _with_first(a.astype(float), math.inf)),
            _derived(
                "-inf in the first element", lambda a: _with_first(a.astype(float), -math.inf)
            ),
            _derived("1e308 everywhere", lambda a: np.full(a.shape, 1e308), extreme=True),
            _derived("5e-324 everywhere", lambda a: np.full(a.shape, 5e-324), extreme=True),
            _derived(
                "1e308 in the first element",
                lambda a: _with_first(a.astype(float), 1e308),
                extreme=True,
            ),
            _derived("zeros", lambda a: np.zeros(a.shape), extreme=True),
            _derived("negated", lambda a: -a.astype(float), extreme=True),
            _derived("scaled by 1e300", lambda a: a.astype(float) * 1e300, extreme=True),
            _derived(
                "a huge int in an object array", lambda a: _with_first(a.astype(object), 10**400)
            ),
        ]
    else:
        out += [
            _derived("as float 0/1", lambda a: a.astype(float)),
            _derived("as 0.5 everywhere", lambda a: np.full(a.shape, 0.5)),
            _derived("as int 2", lambda a: np.full(a.shape, 2)),
            _derived("all True", lambda a: np.ones(a.shape, dtype=bool), extreme=True),
            _derived("all False", lambda a: np.zeros(a.shape, dtype=bool), extreme=True),
        ]
    return [*out, h("a scalar 1.0", 1.0), *GARBAGE]


# --------------------------------------------------------------------------- kinds


class Kind:
    """What an argument must be: its hostile catalogue and what it must refuse.

    ``must_reject(value, tags)`` returns why a value has to be refused (or None);
    ``allow`` lists the non-finite tags (``nan``, ``posinf``, ``neginf``) the kind
    accepts; ``optional`` makes None valid.
    """

    name = "value"
    refuse_always = frozenset({"mapping", "opaque", "complex", "ragged", "nonnumeric"})

    def __init__(
        self,
        *,
        optional: bool = False,
        allow: Iterable[str] = (),
        extra: Iterable[Hostile] = (),
        allowed_errors: tuple[type[BaseException], ...] = (),
    ) -> None:
        self.optional = optional
        self.allow = frozenset(allow)
        self.extra = list(extra)
        self.allowed_errors = allowed_errors

    def __repr__(self) -> str:
        opt = ", optional" if self.optional else ""
        return f"{type(self).__name__}({self.name}{opt})"

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        return list(self.extra)

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        if "none" in tags and not self.optional:
            return "None for a required argument"
        bad = tags & self.refuse_always
        if bad:
            return f"a {sorted(bad)[0]} value"
        nonfinite = tags & {"nan", "posinf", "neginf", "overflow"}
        if nonfinite - self.allow:
            return f"a non-finite value ({sorted(nonfinite - self.allow)[0]})"
        return None


class Real(Kind):
    name = "a real number"
    refuse_always = Kind.refuse_always | {
        "str",
        "bool",
        "sequence",
        "navkit",
        "callable",
        "path",
        "bool_array",
    }

    def __init__(
        self, *, integer: bool = False, expensive: tuple[int, int] | None = None, **kw: Any
    ) -> None:
        super().__init__(**kw)
        self.integer = integer
        # (low, high): valid integers in (low, high] only cost time (a number of
        # trials to run): generated ones are not tried, as the watchdog would take
        # a long valid run for a hang. Those beyond high must still be refused.
        self.expensive = expensive

    def costly(self, value: Any) -> bool:
        """Whether ``value`` is a valid integer that would only make the call long."""
        if self.expensive is None or isinstance(value, (bool, np.bool_)):
            return False
        low, high = self.expensive
        return isinstance(value, numbers.Integral) and low < int(value) <= high

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        return _scalar_hostiles(self.integer) + _wrong_objects()[:1] + super().catalogue(valid)

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        why = super().must_reject(value, tags)
        if why is None and self.integer and "fraction" in tags:
            return "a non-integral number for an integer"
        return why


#: A number of trials to run (``Scenario.run``, ``sweep``): every valid count up to
#: the documented maximum is accepted, and above 8 it only makes the call long (43
#: ``IndoorNav`` tours take about 10 s on a slow CI machine: the watchdog's limit).
TRIALS = Real(integer=True, optional=True, expensive=(8, _MAX_TRIALS))


class Flag(Kind):
    name = "a bool"

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        return [
            h("'no'", "no"),
            h("'False'", "False"),
            h("1", 1),
            h("0", 0),
            h("2", 2),
            h("1.0", 1.0),
            h("nan", math.nan),
            h("np.array([True])", np.array([True])),
            Hostile(
                "the same as np.bool_",
                lambda v, _c: np.bool_(v) if isinstance(v, bool) else SKIP,
                equivalent=True,
            ),
            h("[]", []),
            *GARBAGE,
            *super().catalogue(valid),
        ]

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        if value is None and self.optional:
            return None
        if isinstance(value, (bool, np.bool_)):
            return None
        return f"a {type(value).__name__} for a bool"


class Array(Kind):
    """A real array (or scalar) argument; ``boolean`` for masks."""

    name = "a real array"
    refuse_always = Kind.refuse_always | {"str", "navkit", "callable", "path", "bool"}

    def __init__(self, *, boolean: bool = False, **kw: Any) -> None:
        super().__init__(**kw)
        self.boolean = boolean
        if boolean:
            self.name = "a boolean array"

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        return array_hostiles(self.boolean) + _wrong_objects()[:2] + super().catalogue(valid)

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        why = super().must_reject(value, tags)
        if why is None and not self.boolean and "bool_array" in tags:
            return "a boolean array for a real one"
        return why


class PoseLike(Kind):
    """A Pose2D/Twist2D or a sequence of three numbers."""

    refuse_always = Kind.refuse_always | {"str", "bool", "callable", "path", "bool_array", "scalar"}

    def __init__(self, cls_name: str, **kw: Any) -> None:
        super().__init__(**kw)
        self.cls_name = cls_name
        self.name = f"a {cls_name} or 3 numbers"

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        return [
            Hostile("the same as a list", lambda v, _c: _spell(_triple(v), list), equivalent=True),
            Hostile(
                "the same as a tuple", lambda v, _c: _spell(_triple(v), tuple), equivalent=True
            ),
            Hostile(
                "the same as an array", lambda v, _c: _spell(_triple(v), np.array), equivalent=True
            ),
            Hostile(
                "the same, read-only array",
                lambda v, _c: _spell(_triple(v), lambda t: _readonly(np.array(t))),
                equivalent=True,
            ),
            h("[1.0, 2.0]", [1.0, 2.0]),
            h("[1, 2, 3, 4]", [1.0, 2.0, 3.0, 4.0]),
            h("[nan, 0, 0]", [math.nan, 0.0, 0.0]),
            h("[inf, 0, 0]", [math.inf, 0.0, 0.0]),
            h("[0, 0, inf]", [0.0, 0.0, math.inf]),
            h("[1e308, 1e308, 0]", [1e308, 1e308, 0.0], extreme=True),
            h("[-1e308, 1e308, 1e308]", [-1e308, 1e308, 1e308], extreme=True),
            h("[5e-324, 5e-324, 5e-324]", [5e-324, 5e-324, 5e-324], extreme=True),
            h("[1e300, -1e300, 3.0]", [1e300, -1e300, 3.0], extreme=True),
            h("['1', '2', '3']", ["1", "2", "3"]),
            h("[1+1j, 0, 0]", [1 + 1j, 0.0, 0.0]),
            h("[True, False, True]", [True, False, True]),
            h("np.zeros((1, 3))", np.zeros((1, 3))),
            h("a scalar 1.0", 1.0),
            *GARBAGE,
            *_wrong_objects(),
            *super().catalogue(valid),
        ]

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        if is_navkit_object(value):
            if type(value).__name__ == self.cls_name:
                return None
            return f"a {type(value).__name__} for a {self.cls_name}"
        return super().must_reject(value, tags)


def _triple(v: Any) -> Any:
    if v is None or isinstance(v, Call):
        return SKIP
    if hasattr(v, "as_array"):
        return [float(x) for x in v.as_array()]
    return [float(x) for x in np.asarray(v, dtype=float).ravel()[:3]]


class Cell(Kind):
    """An integer (row, col) pair (or a Field D* node)."""

    name = "an integer pair"
    refuse_always = Kind.refuse_always | {
        "str",
        "bool",
        "navkit",
        "callable",
        "path",
        "bool_array",
        "scalar",
    }

    def __init__(self, *, integer: bool = True, **kw: Any) -> None:
        super().__init__(**kw)
        self.integer = integer

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        return [
            Hostile("the same as a list", lambda v, _c: _spell(_pair(v), list), equivalent=True),
            Hostile(
                "the same as an array", lambda v, _c: _spell(_pair(v), np.array), equivalent=True
            ),
            Hostile(
                "the same as numpy ints",
                lambda v, _c: _spell(_pair(v), lambda p: tuple(np.int32(i) for i in p)),
                equivalent=True,
            ),
            h("(-1, 0)", (-1, 0), extreme=True),
            h("(0, -1)", (0, -1)),
            h("(10**6, 0)", (10**6, 0), extreme=True),
            h("(2**63, 0)", (2**63, 0)),
            h("(10**400, 0)", (10**400, 0)),
            h("(1.5, 0)", (1.5, 0)),
            h("(nan, 0)", (math.nan, 0)),
            h("(inf, 0)", (math.inf, 0)),
            h("(True, False)", (True, False)),
            h("{0: 1, 1: 2}", {0: 1, 1: 2}),
            h("(1, 2, 3)", (1, 2, 3)),
            h("(1,)", (1,)),
            h("[[1, 2]]", [[1, 2]]),
            h("'12'", "12"),
            h("(1+0j, 0)", (1 + 0j, 0)),
            h("a scalar 1", 1),
            *GARBAGE,
            *_wrong_objects()[:1],
            *super().catalogue(valid),
        ]

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        why = super().must_reject(value, tags)
        if why is None and self.integer and "fraction" in tags:
            return "a non-integral number in a cell"
        return why


def _pair(v: Any) -> Any:
    if v is None:
        return SKIP
    a = np.asarray(v).ravel()
    if a.dtype.kind not in "iu":
        return SKIP
    return int(a[0]), int(a[1])


def _spell(value: Any, how: Callable[[Any], Any]) -> Any:
    return SKIP if value is SKIP else how(value)


class Obj(Kind):
    """A navkit object of a given class (or its subclasses)."""

    def __init__(self, cls: type | tuple[type, ...], **kw: Any) -> None:
        super().__init__(**kw)
        self.cls = cls
        names = cls if isinstance(cls, tuple) else (cls,)
        self.name = "a " + " or ".join(c.__name__ for c in names)

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        return GARBAGE + _wrong_objects() + [h("1.0", 1.0), h("[]", [])] + super().catalogue(valid)

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        if value is None and self.optional:
            return None
        if isinstance(value, self.cls):
            return None
        return f"a {type(value).__name__} for {self.name}"


class Choice(Kind):
    """One of a few strings (or values)."""

    def __init__(self, *options: Any, callable_ok: bool = False, **kw: Any) -> None:
        super().__init__(**kw)
        self.options = options
        self.callable_ok = callable_ok
        self.name = "one of " + ", ".join(map(repr, options))

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        first = self.options[0]
        out = [
            h("'nope'", "nope"),
            h("''", ""),
            h("1", 1),
            h("[first]", [first]),
            h("nan", math.nan),
        ]
        if isinstance(first, str):
            out += [
                h("upper-case", first.upper()),
                h("bytes", first.encode()),
                h("padded", f" {first} "),
            ]
        return out + GARBAGE + super().catalogue(valid)

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        if value is None and self.optional:
            return None
        if self.callable_ok and callable(value) and not isinstance(value, type):
            return None
        try:
            if any(type(value) is type(o) and value == o for o in self.options):
                return None
        except Exception:
            pass
        return f"{short(value)} is not {self.name}"


class Text(Kind):
    """A free text (a message, an argument name): anything printable is fine."""

    name = "a text"

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        return [
            h("''", ""),
            h("'\\x00'", "\x00"),
            h("unicode", "ü地図"),
            h("123", 123),
            *GARBAGE[:1],
        ]

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        return None


class Ignored(Kind):
    """A parameter not worth fuzzing (the enum functional API's ``names=``, ``module=``...)."""

    name = "ignored"

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        return []

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        return None


class Anything(Kind):
    """Any object (a message look-alike, shapely geometry): only the exception types count."""

    name = "any object"

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        return (
            GARBAGE
            + _wrong_objects()
            + [h("1.0", 1.0), h("[]", []), h("[None]", [None])]
            + super().catalogue(valid)
        )

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        if value is None and not self.optional:
            return "None for a required argument"
        if tags & {"str", "complex", "opaque", "mapping", "scalar"}:
            return f"a {type(value).__name__}"
        return None


class Function(Kind):
    """A user callable ``f(x) -> array``; hostile ones return NaN, wrong shapes, junk."""

    name = "a function"

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        nan_tag = frozenset({"nan"})
        return [
            h("returns NaN", lambda x: np.full(np.shape(x), math.nan), tags=nan_tag),
            h("returns inf", lambda x: np.full(np.shape(x), math.inf), tags=frozenset({"posinf"})),
            h("returns x * 1e308", lambda x: np.asarray(x) * 1e308 + 1e308, extreme=True),
            h("returns the wrong length", lambda x: np.asarray(x)[:-1]),
            h("returns a str", lambda x: "abc"),
            h("returns None", lambda x: None),
            h("returns complex", lambda x: np.asarray(x) * (1 + 1j)),
            h("returns a 2-D array", lambda x: np.atleast_2d(x)),
            h("returns a list", lambda x: list(np.asarray(x)), equivalent=False),
            h("returns bools", lambda x: np.asarray(x) > 0),
            h("a class", object),
            *GARBAGE,
            h("1.0", 1.0),
            *super().catalogue(valid),
        ]

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        if value is None and self.optional:
            return None
        if callable(value) and not isinstance(value, type):
            return None
        return f"a {type(value).__name__} for a function"


class MatrixOrFunction(Array):
    """A Jacobian: an array, or a function returning it."""

    name = "an array or a function"

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        return super().catalogue(valid) + Function().catalogue(valid)[:8]

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        if callable(value) and not isinstance(value, type) and not is_navkit_object(value):
            return None
        return super().must_reject(value, tags)


class IntSequence(Kind):
    """An iterable of integer indices."""

    name = "integer indices"
    refuse_always = Kind.refuse_always | {"str", "navkit", "bool_array", "scalar", "bool"}

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        return [
            h("[0.5]", [0.5]),
            h("['a']", ["a"]),
            h("[True]", [True]),
            h("[-1]", [-1], extreme=True),
            h("[99]", [99], extreme=True),
            h("[0, 0]", [0, 0]),
            h("[10**400]", [10**400]),
            h("[nan]", [math.nan]),
            h("{0: 1}", {0: 1}),
            h("range(2)", range(2)),
            h("np.array([0])", np.array([0])),
            h("a scalar 0", 0),
            Hostile("iter([0])", lambda _v, _c: iter([0])),
            *GARBAGE,
            *super().catalogue(valid),
        ]

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        if value is None and self.optional:
            return None
        if isinstance(value, (str, bytes)) or not isinstance(value, Iterable):
            return f"a {type(value).__name__} for integer indices"
        if isinstance(value, (list, tuple, np.ndarray)):
            bad = tags & {
                "fraction",
                "str",
                "complex",
                "bool_array",
                "nonnumeric",
                "nan",
                "overflow",
            }
            if bad:
                return f"an index that is not an integer ({sorted(bad)[0]})"
        return None


class FileKind(Kind):
    """A path to read, with malformed files to try (each built per case in ``ctx.tmp``)."""

    name = "a file to read"

    def __init__(self, files: Sequence[tuple[str, Callable[[Path], Path]]] = (), **kw: Any) -> None:
        super().__init__(allowed_errors=(FileNotFoundError,), **kw)
        self.files = list(files)

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        out = [
            Hostile("a missing file", lambda _v, c: c.tmp / "missing.yaml"),
            Hostile("a directory", lambda _v, c: c.tmp),
            Hostile("an empty file", lambda _v, c: _write(c.tmp / "empty.txt", b"")),
            Hostile("the same as a str", lambda v, _c: str(v), equivalent=True),
            Hostile(
                "random bytes", lambda _v, c: _write(c.tmp / "junk.bin", bytes(range(256)) * 4)
            ),
            h("a file name with a NUL", "a\x00b.yaml"),
            h("3.0", 3.0),
            *GARBAGE[:7],
        ]
        for label, make in self.files:
            out.append(
                Hostile(label, lambda _v, c, m=make: m(c.tmp), tags=frozenset({"malformed"}))
            )
        return out + super().catalogue(valid)

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        if "malformed" in tags:
            return "a malformed file"
        if isinstance(value, (str, os.PathLike)) and not isinstance(value, bytes):
            p = Path(value) if "\x00" not in str(value) else None
            if p is None or not p.is_file() or p.stat().st_size == 0:
                return "a path that is not a readable file"
            if p.name == "junk.bin":
                return "a file of random bytes"
            return None
        return f"a {type(value).__name__} for a path"


def _write(path: Path, data: bytes | str) -> Path:
    if isinstance(data, str):
        path.write_text(data, encoding="utf-8")
    else:
        path.write_bytes(data)
    return path


class OutPath(Kind):
    """A path to write a map to (inside the case's folder)."""

    name = "a map path to write"

    def __init__(self, **kw: Any) -> None:
        super().__init__(allowed_errors=(FileNotFoundError,), **kw)

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        return [
            Hostile("a .pgm path", lambda _v, c: c.tmp / "map.pgm"),
            Hostile("a .PGM path", lambda _v, c: c.tmp / "map.PGM"),
            Hostile("the folder itself", lambda _v, c: c.tmp),
            Hostile("a missing folder", lambda _v, c: c.tmp / "no" / "such" / "map.yaml"),
            Hostile(
                "an existing user image as the YAML",
                lambda _v, c: _write(c.tmp / "user.png", b"\x89PNG\r\n\x1a\n"),
            ),
            Hostile("the same as a str", lambda v, _c: str(v), equivalent=True),
            Hostile("a name with a '#'", lambda _v, c: c.tmp / "my map #2.yaml", equivalent=True),
            Hostile("a name with '['", lambda _v, c: c.tmp / "[map].yaml", equivalent=True),
            Hostile("a name with a NUL", lambda _v, c: str(c.tmp / "a\x00b.yaml")),
            h("''", ""),
            h("3.0", 3.0),
            h("None", None),
            h("b'm.yaml'", b"m.yaml"),
            h("{}", {}),
            h("object()", object()),
            *super().catalogue(valid),
        ]

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        if isinstance(value, (str, os.PathLike)) and not isinstance(value, bytes):
            text = str(value)
            if not text or "\x00" in text:
                return "an empty path or one with a NUL"
            p = Path(text)
            if p.suffix.lower() == ".pgm" or p.is_dir() or p.name == "user.png":
                return "a path that would overwrite an image or is a folder"
            return None
        return f"a {type(value).__name__} for a path"


class Namespace(Kind):
    """A message look-alike (SimpleNamespace): each field in turn gets junk or goes missing."""

    name = "a message"
    JUNK: tuple[tuple[str, Any], ...] = (
        ("None", None),
        ("nan", math.nan),
        ("inf", math.inf),
        ("-1", -1),
        ("10**12", 10**12),
        ("'abc'", "abc"),
        ("[]", []),
        ("1+1j", 1 + 1j),
        ("1e308", 1e308),
        ("5e-324", 5e-324),
        ("10**400", 10**400),
    )

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        out: list[Hostile] = []
        for path in _leaf_fields(valid) if isinstance(valid, types.SimpleNamespace) else []:
            dotted = ".".join(path)
            # Whether a field may be missing or odd is the reader's choice; only the
            # exception types and the output are checked.
            out.append(Hostile(f"{dotted} missing", lambda v, _c, p=path: _drop_field(v, p)))
            for label, value in self.JUNK:
                out.append(
                    Hostile(
                        f"{dotted}={label}",
                        lambda v, _c, p=path, x=value: _set_field(v, p, x),
                        tags=frozenset({"nan"} if label == "nan" else ()),
                    )
                )
        return out + GARBAGE + super().catalogue(valid)

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        if value is None:
            return "None for a message"
        if tags & {"str", "complex", "mapping", "scalar"} or type(value) is object:
            return f"a {type(value).__name__} for a message"
        return None


def _leaf_fields(ns: Any, prefix: tuple[str, ...] = ()) -> list[tuple[str, ...]]:
    out = []
    for k, v in vars(ns).items():
        if isinstance(v, types.SimpleNamespace):
            out += _leaf_fields(v, (*prefix, k))
        else:
            out.append((*prefix, k))
    return out


def _clone_ns(ns: Any) -> Any:
    return types.SimpleNamespace(
        **{
            k: _clone_ns(v) if isinstance(v, types.SimpleNamespace) else v
            for k, v in vars(ns).items()
        }
    )


def _set_field(ns: Any, path: tuple[str, ...], value: Any) -> Any:
    out = _clone_ns(ns)
    target = out
    for part in path[:-1]:
        target = getattr(target, part)
    setattr(target, path[-1], value)
    return out


def _drop_field(ns: Any, path: tuple[str, ...]) -> Any:
    out = _clone_ns(ns)
    target = out
    for part in path[:-1]:
        target = getattr(target, part)
    delattr(target, path[-1])
    return out


class SequenceOf(Kind):
    """A sequence of navkit objects of one class (or of a kind of value)."""

    def __init__(self, cls: type | tuple[type, ...], **kw: Any) -> None:
        super().__init__(**kw)
        self.cls = cls
        self.name = f"a sequence of {getattr(cls, '__name__', cls)}"

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        return [
            h("[]", []),
            h("()", ()),
            h("[None]", [None]),
            h("[1.0]", [1.0]),
            h("['a']", ["a"]),
            Hostile("a list of the same", lambda v, _c: list(v), equivalent=True),
            Hostile("a generator of the same", lambda v, _c: (x for x in v)),
            Hostile("with a wrong object", lambda v, _c: [*v, object()]),
            *GARBAGE,
            *_wrong_objects(),
            *super().catalogue(valid),
        ]

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        if value is None and self.optional:
            return None
        if isinstance(value, (str, bytes, Mapping)) or not isinstance(value, Iterable):
            return f"a {type(value).__name__} for {self.name}"
        if isinstance(value, (list, tuple)) and not all(
            isinstance(v, (self.cls, Call))
            for v in value  # lazy elements are built right
        ):
            return f"an element that is not {getattr(self.cls, '__name__', self.cls)}"
        return None


# Kinds inferred from annotations (strings, thanks to ``from __future__ import annotations``).
def infer_kind(annotation: Any) -> Kind | None:
    text = annotation if isinstance(annotation, str) else getattr(annotation, "__name__", "")
    text = text.replace(" ", "")
    optional = text.endswith("|None")
    core = text.removesuffix("|None")
    simple: dict[str, Callable[[], Kind]] = {
        "float": lambda: Real(optional=optional),
        "int": lambda: Real(integer=True, optional=optional),
        "bool": lambda: Flag(optional=optional),
        "ArrayLike": lambda: Array(optional=optional),
        "FloatArray": lambda: Array(optional=optional),
        "NDArray[np.float64]": lambda: Array(optional=optional),
        "BoolArray": lambda: Array(boolean=True, optional=optional),
        "Pose2D|ArrayLike": lambda: PoseLike("Pose2D", optional=optional),
        "Twist2D|ArrayLike": lambda: PoseLike("Twist2D", optional=optional),
    }
    if core in simple:
        return simple[core]()
    for module_name in (
        "navkit.mapping",
        "navkit.kinematics",
        "navkit.estimation",
        "navkit.planning",
        "navkit.geometry",
        "navkit.behaviours",
    ):
        module = __import__(module_name, fromlist=["__all__"])
        obj = getattr(module, core, None)
        if inspect.isclass(obj):
            return Obj(obj, optional=optional)
    return None


# --------------------------------------------------------------------------- checks


def short(value: Any, limit: int = 70) -> str:
    """A short repr of a value for reports."""
    if isinstance(value, np.ndarray):
        body = np.array2string(value.ravel()[:4], threshold=4, precision=3)
        flag = "" if value.flags.writeable else ", read-only"
        more = "…" if value.size > 4 else ""
        text = f"array({body}{more}, shape={value.shape}, dtype={value.dtype}{flag})"
    elif isinstance(value, Path):
        text = f"Path({value.name!r})"
    elif isinstance(value, types.FunctionType) and value.__name__ == "<lambda>":
        text = "<lambda>"
    elif isinstance(value, int) and not isinstance(value, bool) and abs(value) > 10**20:
        text = f"int(~1e{len(str(abs(value))) - 1})"
    else:
        try:
            text = repr(value)
        except Exception:
            text = f"<{type(value).__name__}>"
    return text if len(text) <= limit else text[: limit - 1] + "…"


_SCALARS = (bool, int, str, bytes, type(None))


def nonfinite(value: Any, depth: int = 0, seen: set[int] | None = None) -> set[str]:
    """``{'nan', 'inf'}`` subsets found anywhere in a value (objects' public state included)."""
    t = type(value)
    if t is float:
        return set() if math.isfinite(value) else ({"nan"} if math.isnan(value) else {"inf"})
    if t in _SCALARS:
        return set()
    if t is np.ndarray:
        kind = value.dtype.kind
        if kind in "fc":
            out = set()
            if value.size:
                if np.isnan(value).any():
                    out.add("nan")
                if np.isinf(value).any():
                    out.add("inf")
            return out
        if kind != "O":
            return set()
    seen = set() if seen is None else seen
    if id(value) in seen or depth > 4:
        return set()
    seen.add(id(value))
    if isinstance(value, (np.bool_, enum.Enum)):
        return set()
    if isinstance(value, np.ndarray):  # object arrays
        out = set()
        for item in value.ravel()[:200]:
            out |= nonfinite(item, depth + 1, seen)
        return out
    if isinstance(value, (numbers.Real, numbers.Complex)):
        try:
            c = complex(value)
        except (OverflowError, TypeError):
            return set()
        out = set()
        if math.isnan(c.real) or math.isnan(c.imag):
            out.add("nan")
        if math.isinf(c.real) or math.isinf(c.imag):
            out.add("inf")
        return out
    if isinstance(value, (list, tuple)):
        out = set()
        for item in value[:200]:
            out |= nonfinite(item, depth + 1, seen)
        return out
    if isinstance(value, Mapping):
        return nonfinite(list(value.values()), depth + 1, seen)
    if is_navkit_object(value):
        out = set()
        for _, item in public_state(value):
            out |= nonfinite(item, depth + 1, seen)
        return out
    return set()


_DATA_NAMES: dict[type, list[str]] = {}


def _data_names(obj: Any) -> list[str]:
    """Public data attributes and properties of a navkit object (cached per class)."""
    cls = type(obj)
    names = _DATA_NAMES.get(cls)
    if names is None:
        names = []
        for name in sorted(dir(obj)):
            if name.startswith("_"):
                continue
            raw = inspect.getattr_static(cls, name, None)
            if inspect.isfunction(raw) or isinstance(raw, (classmethod, staticmethod)):
                continue
            if isinstance(raw, enum.Enum):
                continue
            names.append(name)
        if not hasattr(obj, "__dict__"):  # slotted: the names cannot vary per instance
            _DATA_NAMES[cls] = names
    return names


def public_state(obj: Any) -> list[tuple[str, Any]]:
    """``(name, value)`` of every public data attribute and property of a navkit object."""
    out = []
    for name in _data_names(obj):
        try:
            value = getattr(obj, name)
        except Exception as exc:
            value = ("<raises>", type(exc).__name__)
        if inspect.ismethod(value) or inspect.isbuiltin(value):
            continue
        out.append((name, value))
    return out


def snapshot(value: Any, depth: int = 0) -> Any:
    """A deep, comparable copy of a value (navkit objects by their public state)."""
    t = type(value)
    if t in _SCALARS or t is float:
        return value
    if t is np.ndarray:
        return ("ndarray", value.dtype.str, value.shape, bool(value.flags.writeable), value.copy())
    if t is list or t is tuple:
        return (t.__name__, [snapshot(v, depth + 1) for v in value])
    if isinstance(value, dict):
        return ("dict", {k: snapshot(v, depth + 1) for k, v in value.items()})
    if isinstance(value, types.SimpleNamespace):
        return ("ns", {k: snapshot(v, depth + 1) for k, v in vars(value).items()})
    if is_navkit_object(value) and depth < 3:
        return (t.__name__, [(n, snapshot(v, depth + 1)) for n, v in public_state(value)])
    if isinstance(value, (numbers.Number, str, bytes, enum.Enum, Path)):
        return value
    return ("id", id(value))


def same(a: Any, b: Any) -> bool:
    """Whether two snapshots are equal (NaN equals NaN)."""
    if a is b:
        return True
    ta, tb = type(a), type(b)
    if ta is not tb:
        return False
    if ta is float:
        return a == b or (math.isnan(a) and math.isnan(b))
    if ta in _SCALARS:
        return bool(a == b)
    if ta is np.ndarray:
        if a.shape != b.shape or a.dtype != b.dtype:
            return False
        if a.dtype.kind in "fc":
            return bool(np.array_equal(a, b, equal_nan=True))
        try:
            return bool(np.array_equal(a, b))
        except Exception:
            return a.tolist() == b.tolist()
    if ta is tuple or ta is list:
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b, strict=True))
    if ta is dict:
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, numbers.Number):
        try:
            return bool(a == b) or (cmath_isnan(a) and cmath_isnan(b))
        except (TypeError, OverflowError):
            return False
    try:
        return bool(a == b)
    except Exception:
        return False


def folder_state(folder: Path) -> dict[str, bytes]:
    out = {}
    for p in sorted(folder.rglob("*")):
        if p.is_file():
            out[str(p.relative_to(folder))] = p.read_bytes()
    return out


def allowed_error(exc: BaseException, extra: tuple[type[BaseException], ...]) -> bool:
    if isinstance(exc, NavkitError):
        return True
    if type(exc) in (ValueError, TypeError):
        return True
    if type(exc).__module__.startswith("navkit") and isinstance(exc, (ValueError, TypeError)):
        return True
    return any(type(exc) is e for e in extra)


def cmath_isnan(x: Any) -> bool:
    try:
        c = complex(x)
    except (TypeError, OverflowError):
        return False
    return math.isnan(c.real) or math.isnan(c.imag)


class Hang(BaseException):
    """Raised by the watchdog when a call runs past its bound (see :func:`watchdog`)."""


@contextlib.contextmanager
def watchdog(seconds: float, *, wall: float | None = None) -> Iterator[None]:
    """Raise :class:`Hang` once the block has used ``seconds`` s of CPU time.

    The bound is the process's CPU time (``ITIMER_PROF``: every thread's, so a
    parallel kernel's threads add up), not wall-clock time: on a 2-core machine
    with a load average of 14 a call needing 0.05 s of CPU could take 10 s of
    wall-clock time, and the slow fuzz reported ``DiffDrive.odometry_step_batch``
    as hanging (review 45). A call blocked without computing (a deadlock, a wait
    for ever) burns no CPU time: ``wall`` s of wall-clock time (default the
    larger of ``WALL_TIMEOUT_S`` and ``seconds``) end it instead.

    numba's time is not counted: while a thread holds numba's compiler lock
    (compiling a kernel, or loading it from the cache) both bounds are
    ``COMPILE_TIMEOUT_S``, and the block's start again once numba lets go of
    the lock. A hostile value can take a call to a branch or a dtype whose
    kernel no earlier call compiled: with a cold cache on a loaded 2-core
    machine, ``ExtendedKalmanFilter.predict`` with NaN in ``Q`` compiled three
    kernels in 4.6 s of the 10 s a later call gets (review 39).

    Python runs the handler between bytecodes, in whatever frame is running. In
    a garbage-collector callback (hypothesis keeps one), a ``__del__`` method or
    a ``weakref.finalize`` callback an exception is reported as unraisable and
    lost, and the call goes on: there the watchdog tries again ``_RETRY_S``
    later, at most ``_MAX_RETRIES`` times. Where such a place is not told by its
    frame (a plain weak-reference callback: llvmlite's ``on_disposal``, run as
    numba's objects die, was one), the :class:`Hang` Python reports as
    unraisable is caught by the block's ``sys.unraisablehook`` and the watchdog
    tries again the same way. A kernel compiled in nopython mode
    never runs Python's handlers: one that loops for ever is not ended (a kernel
    that returns late is reported as it returns). The :class:`Hang` names the
    bound and the frame it was raised in. Without ``signal.setitimer``
    (Windows) there is no watchdog. Watchdogs do not nest (the inner one's
    compile listener would set the outer's bounds); timers set before the block
    are set again after it, less the time the block took.
    """
    if not hasattr(signal, "setitimer"):
        yield
        return
    bounds = _Bounds(seconds, max(WALL_TIMEOUT_S, seconds) if wall is None else wall)
    try:
        bounds.start()
        with _compiles_not_counted(bounds):
            yield
    finally:
        try:
            bounds.stop()
        except Hang:  # the bound came as the block ended: the call returned, no hang
            bounds.stop()


class _Bounds:
    """The watchdog's two timers and what may set them (see :func:`watchdog`).

    ``guard`` orders the compile listener's calls (any thread's) with the
    block's end and with the raising of the :class:`Hang`; once ``ended`` is set
    nothing sets a timer again (a signal after the handlers are put back would
    meet ``SIG_DFL``: the end of the process). The handler runs in the main
    thread and never waits for ``guard``: where it is taken it tries again.
    """

    def __init__(self, cpu: float, wall: float) -> None:
        self.cpu = cpu
        self.wall = wall
        #: numba compiler-lock holds under way (the lock is re-entrant: nested).
        self.inside = 0
        self.ended = False
        self.retries = 0
        self.guard = threading.Lock()
        self.handlers: list[tuple[int, Any]] = []
        #: Timers set before the block: (which, (value, interval), clock, clock at start).
        self.outer: list[tuple[int, tuple[float, float], Callable[[], float], float]] = []
        self.stopped = False
        self.closing = False
        #: sys.unraisablehook before the block (the block's own catches lost Hangs).
        self.hook: Callable[[Any], object] | None = None
        #: CPU and wall-clock times as the block's bounds were (last) set.
        self.since = (time.process_time(), time.monotonic())

    def arm(self, cpu: float, wall: float) -> None:
        signal.setitimer(signal.ITIMER_PROF, cpu)
        signal.setitimer(signal.ITIMER_REAL, wall)
        self.since = (time.process_time(), time.monotonic())

    def start(self) -> None:
        self.hook = sys.unraisablehook
        sys.unraisablehook = self.lost
        for signum in (signal.SIGPROF, signal.SIGALRM):
            self.handlers.append((signum, signal.getsignal(signum)))
            signal.signal(signum, self.fire)
        for which, value, clock in (
            (signal.ITIMER_PROF, self.cpu, time.process_time),
            (signal.ITIMER_REAL, self.wall, time.monotonic),
        ):
            now = clock()
            self.outer.append((which, signal.setitimer(which, value), clock, now))
        self.since = (time.process_time(), time.monotonic())

    def stop(self) -> None:
        if self.stopped:
            return
        self.closing = True  # (no lost Hang is tried again from here on)
        with self.guard:
            self.ended = True
            self.arm(0, 0)
        for signum, handler in reversed(self.handlers):
            signal.signal(signum, handler)
        if sys.unraisablehook == self.lost and self.hook is not None:
            sys.unraisablehook = self.hook
        self.stopped = True
        for which, (value, interval), clock, then in self.outer:
            if value > 0:
                # A timer due during the block is due now (a zero would clear it).
                signal.setitimer(which, max(value - (clock() - then), 1e-6), interval)

    def lost(self, unraisable: Any) -> None:
        """``sys.unraisablehook`` during the block: a lost :class:`Hang` is tried again.

        Anything else, and a Hang after the retries or the block, goes to the hook
        the block found.
        """
        if (
            isinstance(unraisable.exc_value, Hang)
            and not self.closing
            and self.retries < _MAX_RETRIES
        ):
            with self.guard:
                self.retries += 1
                self.ended = False
                self.arm(_RETRY_S, _RETRY_S)
            return
        if self.hook is not None:
            self.hook(unraisable)

    def fire(self, signum: int, frame: types.FrameType | None) -> None:
        if self.ended:
            return  # a signal on its way as the block ended
        lost_in = _lost_in(frame)
        raising = lost_in is None or self.retries >= _MAX_RETRIES
        if raising and self.guard.acquire(blocking=False):
            try:  # (only the main thread sets ``ended``: it cannot have changed)
                why = self._why(signum, frame, lost_in)
                self.ended = True
                self.arm(0, 0)  # one Hang a block: the caller's report runs in it
            finally:
                self.guard.release()
            raise Hang(why)
        self.retries += 1
        which = signal.ITIMER_PROF if signum == signal.SIGPROF else signal.ITIMER_REAL
        signal.setitimer(which, _RETRY_S)

    def _why(self, signum: int, frame: types.FrameType | None, lost_in: str | None) -> str:
        cpu, wall = time.process_time() - self.since[0], time.monotonic() - self.since[1]
        if self.inside:
            bound = f"still inside numba's compiler lock after {COMPILE_TIMEOUT_S:g} s"
        elif signum == signal.SIGPROF or signal.getitimer(signal.ITIMER_PROF)[0] == 0:
            # Both timers run out in a long kernel, and Python runs SIGALRM's
            # handler (14) before SIGPROF's (27) as it returns: the CPU time is why.
            bound = f"still running after {self.cpu:g} s of CPU time"
        else:
            bound = f"still running after {self.wall:g} s of wall-clock time, waiting"
        text = f"{bound}, at {_frame_text(frame)}; {cpu:.3g} s of CPU time in {wall:.3g} s"
        return text + (f"; in {lost_in}, where it may be lost" if lost_in else "")


#: How soon the watchdog tries again where its :class:`Hang` would be lost (s).
_RETRY_S = 0.05
_MAX_RETRIES = 200


def _lost_in(frame: types.FrameType | None) -> str | None:
    """Where an exception raised in ``frame`` is reported as unraisable and lost, if it is."""
    callbacks = {getattr(getattr(cb, "__func__", cb), "__code__", None) for cb in gc.callbacks}
    while frame is not None:
        code = frame.f_code
        if code in callbacks:
            return "a garbage-collector callback"
        if code.co_name == "__del__":
            return "a __del__ method"
        if code is weakref.finalize.__call__.__code__:
            return "a weakref.finalize callback"
        frame = frame.f_back
    return None


def _frame_text(frame: types.FrameType | None) -> str:
    if frame is None:
        return "an unknown point"
    path = Path(frame.f_code.co_filename)
    with contextlib.suppress(ValueError):
        path = path.resolve().relative_to(SRC.parent)
    shown = path if path.parts[:1] == ("navkit",) else path.name
    return f"{shown}:{frame.f_lineno} in {frame.f_code.co_name}"


@contextlib.contextmanager
def _compiles_not_counted(bounds: _Bounds) -> Iterator[None]:
    """Both of the watchdog's timers at ``COMPILE_TIMEOUT_S`` while numba's compiler lock is held.

    numba announces each acquire and release of its compiler lock (re-entrant:
    nested) as a ``"numba:compiler_lock"`` event; before numba is loaded there is
    nothing to listen to (the first call of a spec, which may load it, gets the
    callers' warm-up bound, ``WARM_UP_TIMEOUT_S``). A listener call from another
    thread still under way as the block ends sets no timer after it (the
    watchdog's clearing of the timers would come first, and a signal then meet
    the handler put back: by default, the end of the process).
    """
    event = sys.modules.get("numba.core.event")
    if event is None:
        yield
        return

    class _Compiles(event.Listener):  # type: ignore[misc, name-defined]
        def on_start(self, _event: Any) -> None:
            with bounds.guard:
                bounds.inside += 1
                if not bounds.ended:
                    bounds.arm(COMPILE_TIMEOUT_S, COMPILE_TIMEOUT_S)

        def on_end(self, _event: Any) -> None:
            with bounds.guard:
                bounds.inside -= 1
                if bounds.inside == 0 and not bounds.ended:
                    bounds.arm(bounds.cpu, bounds.wall)

    with event.install_listener("numba:compiler_lock", _Compiles()):
        yield


_LIMIT: list[int] = []


def refresh_memory_limit() -> None:
    """Measure the process's size again (before each spec: thread pools may have grown it)."""
    _LIMIT.clear()


def _address_space_limit() -> int | None:
    """The process's address-space size when first asked, plus ``MEMORY_HEADROOM``."""
    if not _LIMIT:
        try:
            with open("/proc/self/status", encoding="ascii") as f:
                vm = next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmSize"))
        except (OSError, StopIteration, ValueError):
            _LIMIT.append(-1)
        else:
            _LIMIT.append(vm + MEMORY_HEADROOM)
    return _LIMIT[0] if _LIMIT[0] > 0 else None


@contextlib.contextmanager
def memory_limit() -> Iterator[None]:
    """Cap the address space so a missing size check shows as MemoryError, not an OOM kill."""
    limit = _address_space_limit()
    try:
        soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    except (OSError, ValueError, AttributeError):
        limit = None
    if limit is None:
        yield
        return
    if hard != resource.RLIM_INFINITY:
        limit = min(limit, hard)
    resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    try:
        yield
    finally:
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


# --------------------------------------------------------------------------- specs and cases


@dataclass
class Spec:
    """How to fuzz one public callable.

    Parameters
    ----------
    name
        Canonical public name (``navkit.geometry.Pose2D.compose``).
    make
        ``make(ctx) -> Call``: a fresh valid call (a new receiver every time).
    kinds
        Kinds of parameters whose annotation does not say enough (``{"dt": Real()}``).
    inf_ok, nan_ok
        Why the output may hold infinities / NaN from finite input (documented
        answers), or a predicate on the result saying whether it may. They concern
        the output only, never the receiver's state.
    mutates
        Parameters (``"self"`` for the receiver) the call is documented to modify.
    expect_error
        The valid call itself must raise this (abstract classes, protocols).
    degenerate
        ``degenerate(receiver) -> bool``: an accepted hostile call left the
        receiver in a state that float64 cannot carry further (a covariance
        whose eigenvalues lie more than 1/eps apart); the valid call may then
        raise ``FilterError`` (the documented answer) instead of working.
    """

    name: str
    make: Callable[[Ctx], Call]
    kinds: dict[str, Kind] = field(default_factory=dict)
    inf_ok: str | Callable[[Any], bool] | None = None
    nan_ok: str | Callable[[Any], bool] | None = None
    mutates: tuple[str, ...] = ()
    expect_error: type[BaseException] | None = None
    degenerate: Callable[[Any], bool] | None = None


SPECS: dict[str, Spec] = {}
NOT_FUZZED: dict[str, str] = {}


def spec(name: str, make: Callable[[Ctx], Call], **kw: Any) -> Spec:
    """Register a spec (see :class:`Spec`)."""
    if name in SPECS:
        raise ValueError(f"two specs for {name}")
    SPECS[name] = out = Spec(name, make, **kw)
    return out


def kind_for(c: Call, param: inspect.Parameter) -> Kind | None:
    """The kind of a parameter: the spec of the called function says, else its annotation."""
    key = c.key
    if key is not None and key in SPECS and param.name in SPECS[key].kinds:
        return SPECS[key].kinds[param.name]
    return infer_kind(param.annotation)


@dataclass(frozen=True)
class Slot:
    """Where a hostile value goes: a path of parameter names through the call tree."""

    path: tuple[str, ...]

    def __str__(self) -> str:
        return ".".join(self.path)


def slots(
    c: Call, depth: int = 0, prefix: tuple[str, ...] = ()
) -> list[tuple[Slot, Kind, Any, bool]]:
    """``(slot, kind, valid value, nested)`` for every parameter in the call tree."""
    out = []
    for p in c.parameters():
        kind = kind_for(c, p)
        value = c.value_of(p)
        if isinstance(value, Call):
            if depth < 2:
                out += slots(value, depth + 1, (*prefix, p.name))
            if kind is None:
                kind = Anything()
            value = None  # the whole object is replaced by garbage only
        if kind is not None:
            out.append((Slot((*prefix, p.name)), kind, value, depth > 0))
    if c.method is not None and isinstance(c.target, Call) and depth < 2:
        out += slots(c.target, depth + 1, (*prefix, "self"))
    return out


def replace(c: Call, path: tuple[str, ...], value: Any) -> None:
    """Put ``value`` at ``path`` in the (copied) call tree ``c``."""
    head, rest = path[0], path[1:]
    if head == "self":
        assert isinstance(c.target, Call)
        replace(c.target, rest, value)
        return
    if rest:
        inner = c.arguments[head]
        assert isinstance(inner, Call)
        replace(inner, rest, value)
        return
    c.arguments[head] = value


def leaves(c: Any, prefix: str = "") -> list[tuple[str, Any]]:
    """Every argument value in the tree that is not itself a lazy call."""
    out: list[tuple[str, Any]] = []
    if isinstance(c, Call):
        if c.method is not None:
            if isinstance(c.target, Call):
                out += leaves(c.target, f"{prefix}self.")
            else:
                out.append((f"{prefix}self", c.target))
        for k, v in c.arguments.items():
            out += leaves(v, f"{prefix}{k}.") if isinstance(v, Call) else [(f"{prefix}{k}", v)]
        if c._raw is not None:
            out += [(f"{prefix}{i}", v) for i, v in enumerate(c._raw[0])]
    return out


@dataclass
class Case:
    slot: Slot | None
    hostile: Hostile | None
    kind: Kind | None
    nested: bool = False

    @property
    def label(self) -> str:
        if self.slot is None or self.hostile is None:
            return "the valid call"
        return f"{self.slot} = {self.hostile.label}"


def cases_for(s: Spec, *, nested_extremes_only: bool = True) -> list[Case]:
    """Every (slot, hostile) pair of a spec's catalogue, valid call first."""
    root = Path(tempfile.mkdtemp(prefix="navkit-fuzz-"))
    try:
        tree = s.make(Ctx(root))
    finally:
        shutil.rmtree(root, ignore_errors=True)
    out = [Case(None, None, None)]
    for slot, kind, _value, nested in slots(tree):
        for hostile in kind.catalogue(_value):
            if nested and nested_extremes_only and not hostile.extreme:
                continue
            out.append(Case(slot, hostile, kind, nested))
    return out


@dataclass
class Failure:
    spec: str
    case: str
    problem: str
    call: str

    @property
    def line(self) -> str:
        return f"{self.call} -> {self.problem}   [{area_of(self.spec)}; {self.spec}; {self.case}]"


@contextlib.contextmanager
def quiet() -> Iterator[None]:
    """Silence warnings (ComplexWarning, overflow...) around many cases at once."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        yield


def run_case(s: Spec, case: Case, root: Path, *, timeout: float = CALL_TIMEOUT_S) -> list[Failure]:
    """Run one case of a spec and return what broke navkit's promise.

    ``timeout``: seconds before a call counts as hanging (the first valid call of a
    spec gets longer: it may compile numba kernels). Run it inside :func:`quiet`.
    """
    ctx = Ctx(root)
    try:
        return _run_case(s, case, ctx, timeout)
    finally:
        if ctx.used:
            shutil.rmtree(ctx.tmp, ignore_errors=True)


def _run_case(s: Spec, case: Case, ctx: Ctx, timeout: float) -> list[Failure]:
    tree = s.make(ctx)
    valid_value = None
    hostile_value: Any = None
    if case.slot is not None and case.hostile is not None:
        valid_value = _value_at(tree, case.slot.path)
        with np.errstate(all="ignore"):
            hostile_value = case.hostile.make(valid_value, ctx)
        if hostile_value is SKIP:
            return []
        replace(tree, case.slot.path, hostile_value)
    rendered: list[str] = []
    failures: list[Failure] = []

    def text() -> str:
        # Rendering is costly: only for failures (the inputs are checked unchanged).
        if not rendered:
            rendered.append(tree.render())
        return rendered[0]

    def fail(problem: str) -> list[Failure]:
        failures.append(Failure(s.name, case.label, problem, text()))
        return failures

    # What the contract asks of this value.
    reject_why = None
    must_accept = False
    if case.hostile is not None and case.kind is not None:
        tags = tags_of(hostile_value) | set(case.hostile.tags)
        reject_why = case.kind.must_reject(hostile_value, tags)
        if case.hostile.must_reject and reject_why is None:
            reject_why = case.hostile.label
        must_accept = case.hostile.equivalent and reject_why is None
    extra_errors = case.kind.allowed_errors if case.kind is not None else ()

    in_leaves = leaves(tree)
    before = [(name, snapshot(v)) for name, v in in_leaves]
    input_nonfinite: set[str] = set()
    for _name, v in in_leaves:
        input_nonfinite |= nonfinite(v)
    if case.hostile is not None:
        input_nonfinite |= {
            "nan" if t == "nan" else "inf"
            for t in case.hostile.tags
            if t in ("nan", "posinf", "neginf")
        }
    files_before = folder_state(ctx.tmp) if ctx.used else {}

    built: list[tuple[str, Any]] = []
    receiver = None
    stage = "building the arguments"
    result: Any = None
    error: BaseException | None = None
    with np.errstate(all="ignore"), memory_limit(), watchdog(timeout):
        try:
            if tree.method is not None:
                stage = "building the receiver"
                receiver = materialize(tree.target, built, "self.")
                if tree.prepare is not None:
                    tree.prepare(receiver)
            args = {k: materialize(v, built, f"{k}.") for k, v in tree.arguments.items()}
            objects_before = [(name, snapshot(o)) for name, o in built]
            receiver_before = snapshot(receiver) if receiver is not None else None
            input_nonfinite |= nonfinite(receiver) if receiver is not None else set()
            for _name, o in built:
                input_nonfinite |= nonfinite(o)
            stage = "the call"
            result = tree.invoke(receiver, args)
            if result is NotImplemented and tree.method in OPERATORS:
                # What Python does with it: ``a + b`` raises TypeError.
                raise TypeError(f"unsupported operand for {tree.method}")
        except Hang as exc:
            return fail(f"hangs ({exc}) during {stage}")
        except BaseException as exc:
            error = exc
    if error is not None:
        if s.expect_error is not None and isinstance(error, s.expect_error):
            return failures
        if isinstance(error, (KeyboardInterrupt, SystemExit)):
            raise error
        if not allowed_error(error, extra_errors):
            return fail(f"{_type_name(error)}: {_msg(error)} (during {stage})")
        if case.slot is None and s.expect_error is None:
            return fail(f"the spec's valid call fails: {type(error).__name__}: {_msg(error)}")
        if must_accept:
            fail(
                "rejects an equivalent spelling of a valid value: "
                f"{type(error).__name__}: {_msg(error)}"
            )
        # Nothing may have changed.
        for (name, snap), (_n, v) in zip(before, in_leaves, strict=True):
            if not same(snap, snapshot(v)):
                fail(f"a failed call modified its input {name}")
        if stage == "the call":
            for (name, snap), (_n, o) in zip(objects_before, built, strict=True):
                if name != "self" and not same(snap, snapshot(o)):
                    fail(f"a failed call changed the public state of {name}")
            if receiver is not None and not same(receiver_before, snapshot(receiver)):
                fail("a failed call changed the receiver's public state")
        if ctx.used and folder_state(ctx.tmp) != files_before:
            fail("a failed call changed files")
        return failures

    if s.expect_error is not None and case.slot is None:
        return fail(f"the valid call was expected to raise {s.expect_error.__name__}")
    if reject_why is not None:
        fail(f"accepted {reject_why}")
    with np.errstate(all="ignore"):
        out_bad = nonfinite(result)
        if receiver is not None:
            out_bad |= {f"{t} in the receiver's state" for t in nonfinite(receiver)}
    nan_ok = s.nan_ok(result) if callable(s.nan_ok) else bool(s.nan_ok)
    inf_ok = s.inf_ok(result) if callable(s.inf_ok) else bool(s.inf_ok)
    for bad in sorted(out_bad):
        base = bad.split(" ")[0]
        in_output = bad == base
        if base == "nan" and "nan" not in input_nonfinite and not (nan_ok and in_output):
            fail(f"NaN in the {_where(bad)} from NaN-free input")
        if base == "inf" and not (input_nonfinite & {"inf", "nan"}) and not (inf_ok and in_output):
            fail(f"infinity in the {_where(bad)} from finite input")
    mutates = set(s.mutates)
    for (name, snap), (_n, v) in zip(before, in_leaves, strict=True):
        if name.split(".")[0] not in mutates and not same(snap, snapshot(v)):
            fail(f"modified its input {name}")
    for (name, snap), (_n, o) in zip(objects_before, built, strict=True):
        if name != "self" and name.split(".")[0] not in mutates and not same(snap, snapshot(o)):
            fail(f"changed the public state of its argument {name}")
    if (
        receiver is not None
        and "self" not in mutates
        and not same(receiver_before, snapshot(receiver))
    ):
        fail("changed the receiver's public state")
    if receiver is not None and "self" in mutates and case.slot is not None:
        failures += _still_usable(s, receiver, ctx, text, case)
    return failures


def _still_usable(
    s: Spec, receiver: Any, ctx: Ctx, text: Callable[[], str], case: Case
) -> list[Failure]:
    """After a successful hostile call, the valid call still works on the same object."""
    fresh = s.make(ctx)
    built: list[tuple[str, Any]] = []
    with np.errstate(all="ignore"), memory_limit(), watchdog(CALL_TIMEOUT_S):
        try:
            args = {k: materialize(v, built, f"{k}.") for k, v in fresh.arguments.items()}
            fresh.invoke(receiver, args)
        except Hang as exc:
            return [Failure(s.name, case.label, f"then the valid call hangs ({exc})", text())]
        except BaseException as exc:
            if isinstance(exc, FilterError) and s.degenerate is not None:
                with np.errstate(all="ignore"):
                    if s.degenerate(receiver):
                        return []
            if isinstance(exc, FilterError) or not allowed_error(exc, ()):
                problem = (
                    "leaves the object unusable: the valid call then raises "
                    f"{type(exc).__name__}: {_msg(exc)}"
                )
                return [Failure(s.name, case.label, problem, text())]
    return []


def _value_at(c: Call, path: tuple[str, ...]) -> Any:
    head, rest = path[0], path[1:]
    if head == "self":
        assert isinstance(c.target, Call)
        return _value_at(c.target, rest)
    param = next(p for p in c.parameters() if p.name == head)
    value = c.value_of(param)
    if rest:
        return _value_at(value, rest)
    return value


def _type_name(exc: BaseException) -> str:
    return f"{type(exc).__module__}.{type(exc).__qualname__}"


def _where(bad: str) -> str:
    """``"nan"`` -> ``"output"``; ``"nan in the receiver's state"`` -> ``"receiver's state"``."""
    return bad.split(" in the ", 1)[1] if " in the " in bad else "output"


def _msg(exc: BaseException) -> str:
    text = str(exc).replace("\n", " ")
    return text if len(text) <= 160 else text[:159] + "…"


# --------------------------------------------------------------------------- generated values


def generated_strategy(kind: Kind, valid: Any) -> Any:
    """A hypothesis strategy of hostile values for a slot (None: the catalogue is enough)."""
    from hypothesis import strategies as st
    from hypothesis.extra import numpy as hnp

    floats = st.floats(allow_nan=True, allow_infinity=True, allow_subnormal=True)
    if isinstance(kind, (Real, Choice)) and not isinstance(kind, Flag):
        numbers_ = st.one_of(floats, st.integers(min_value=-(2**70), max_value=2**70))
        if isinstance(kind, Real) and kind.expensive is not None:
            return numbers_.filter(lambda v: not kind.costly(v))
        return numbers_
    if isinstance(kind, Flag):
        return st.one_of(st.integers(-2, 2), st.text(max_size=3), st.none(), floats)
    if isinstance(kind, PoseLike):
        return st.lists(floats, min_size=2, max_size=4)
    if isinstance(kind, Cell):
        coord = st.one_of(st.integers(-3, 12), st.integers(-(2**65), 2**65), floats)
        return st.tuples(coord, coord)
    if isinstance(kind, Array):
        arr = _as_array(valid)
        dtypes = st.sampled_from(
            [np.float64, np.float32, np.int8, np.int64, np.uint16, np.complex128, np.bool_, "<U2"]
        )
        random_arrays = hnp.arrays(
            dtypes, hnp.array_shapes(min_dims=0, max_dims=3, min_side=0, max_side=4)
        )
        if arr is None or arr.size == 0 or arr.dtype.kind not in "iuf":
            return random_arrays
        base = np.array(arr, dtype=np.float64)

        @st.composite
        def one_element(draw: Any) -> np.ndarray:
            out = base.copy()
            out.flat[draw(st.integers(0, out.size - 1))] = draw(floats)
            return out

        @st.composite
        def scaled(draw: Any) -> np.ndarray:
            with np.errstate(all="ignore"):
                return base * draw(floats)

        return st.one_of(one_element(), scaled(), random_arrays)
    return None
