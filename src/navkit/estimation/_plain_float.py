"""A numba argument type for a fast path's floats: anything else arrives as NaN (private).

Imports numba: kernel modules bind :func:`plain_value` lazily (see below).

A kernel compiled for ``float64`` arguments converts whatever it is given as
``float()`` would: an int, a bool, a NumPy scalar, an object with
``__float__``, even a string (``"1.5"``). A public fast path that hands its
arguments straight to a compiled entry therefore checked in Python that each
was a plain float first (``type(t) is float``: about 70 ns of the five of
:meth:`PlanarFusion.update_odometry
<navkit.estimation.PlanarFusion.update_odometry>`, a tenth of the call). The
compiled entry's conversion of an argument of type :data:`PLAIN_FLOAT` makes
that check in C instead: a Python ``float``, an instance of a float subclass
defined in C (NumPy's ``float64``, whose value is its float's) or an ``int``
that float64 holds exactly (magnitude at most 2**53, which ``float()`` converts
without rounding) gives its value; anything else (a bool, a larger int, a
string, a ``float32``, a NumPy integer, a float subclass defined in Python,
which may override ``__float__``) gives NaN, without calling any of its
methods. A kernel that refuses a NaN argument (as
the online fusion step does, returning its "invalid" status and changing
nothing) thus sends every other type to the caller's general, validating way,
with no exception raised on the way. In a kernel, :func:`plain_value` turns
such an argument into a float64 (the same 64 bits); it also takes a float64,
so a kernel written with it can be called through numba's dispatcher with
plain floats too.

Kernel modules bind :func:`plain_value` with
:func:`navkit._shared.jit.bind_numba_names` (importing them must not import
numba), with a Python equivalent for ``NUMBA_DISABLE_JIT=1``, and ask
:data:`PLAIN_FLOAT` for the signatures of their compiled entries.
"""

from __future__ import annotations

import math
from typing import Any

from llvmlite import ir  # type: ignore[import-untyped]
from numba import extending as _extending
from numba.core import cgutils as _cgutils
from numba.core import types

# Any: numba's code generation helpers are untyped.
cgutils: Any = _cgutils
NativeValue: Any = _extending.NativeValue
models: Any = _extending.models
_unbox: Any = _extending.unbox
_register_model: Any = _extending.register_model
_intrinsic: Any = _extending.intrinsic

__all__ = ["PLAIN_FLOAT", "PlainFloat", "plain_value"]

# CPython's type flag of classes defined in Python (heap types).
_HEAPTYPE = 1 << 9
# The largest magnitude of the ints whose float64 is exact, all below it too.
_EXACT = 2**53


class PlainFloat(types.Type):  # type: ignore[misc, unused-ignore]  # (untyped in numba 0.62)
    """A float64 argument taken from a float (NaN from anything else; see the module)."""

    def __init__(self) -> None:
        super().__init__(name="navkit_plain_float64")


#: The one instance, for signatures.
PLAIN_FLOAT = PlainFloat()


class _PlainFloatModel(models.PrimitiveModel):  # type: ignore[misc]  # (a class of Any)
    """Stored as a double, as float64."""

    def __init__(self, dmm: Any, fe_type: Any) -> None:
        super().__init__(dmm, fe_type, ir.DoubleType())


_register_model(PlainFloat)(_PlainFloatModel)


def _unbox_plain_float(typ: Any, obj: Any, c: Any) -> Any:
    """The value of a float, an exact int or a C-defined float subclass's instance, else NaN."""
    builder = c.builder
    double = ir.DoubleType()
    float_type = c.pyapi.get_c_object("PyFloat_Type")
    obj_type = c.pyapi.get_type(obj)
    value = cgutils.alloca_once_value(builder, ir.Constant(double, math.nan))
    with builder.if_else(builder.icmp_unsigned("==", obj_type, float_type), likely=True) as (
        exact,
        other,
    ):
        with exact:
            # PyFloat_AsDouble reads a float's value and cannot fail.
            builder.store(c.pyapi.float_as_double(obj), value)
        with other:
            _unbox_other(c, obj, obj_type, float_type, value)
    return NativeValue(builder.load(value))


def _unbox_other(c: Any, obj: Any, obj_type: Any, float_type: Any, value: Any) -> None:
    """Store into ``value`` the value of an int or a C-defined float subclass's instance."""
    builder = c.builder
    double = ir.DoubleType()
    int32 = ir.IntType(32)
    int64 = ir.IntType(64)
    int_type = c.pyapi.get_c_object("PyLong_Type")
    with builder.if_else(builder.icmp_unsigned("==", obj_type, int_type)) as (is_int, not_int):
        with is_int:
            # An int that float64 holds exactly (|i| <= 2**53), as float() converts it;
            # larger ones stay NaN (the general way refuses or rounds them, naming them).
            overflow = cgutils.alloca_once_value(builder, ir.Constant(int32, 0))
            as_long_fn = cgutils.get_or_insert_function(
                builder.module, ir.FunctionType(int64, [c.pyapi.pyobj, int32.as_pointer()]),
                "PyLong_AsLongLongAndOverflow",
            )  # fmt: skip
            i = builder.call(as_long_fn, [obj, overflow])
            exact = builder.and_(
                builder.icmp_signed("==", builder.load(overflow), ir.Constant(int32, 0)),
                builder.icmp_unsigned(
                    "<=", builder.add(i, ir.Constant(int64, _EXACT)), ir.Constant(int64, 2 * _EXACT)
                ),
            )
            with builder.if_then(exact):
                builder.store(builder.sitofp(i, double), value)
        with not_int:
            subtype_fn = cgutils.get_or_insert_function(
                builder.module, ir.FunctionType(int32, [c.pyapi.pyobj, c.pyapi.pyobj]),
                "PyType_IsSubtype",
            )  # fmt: skip
            flags_fn = cgutils.get_or_insert_function(
                builder.module, ir.FunctionType(c.pyapi.ulong, [c.pyapi.pyobj]), "PyType_GetFlags"
            )
            subclass = builder.icmp_signed("!=", builder.call(subtype_fn, [obj_type, float_type]),
                                           ir.Constant(int32, 0))  # fmt: skip
            with builder.if_then(subclass):
                flags = builder.call(flags_fn, [obj_type])
                heap = builder.and_(flags, ir.Constant(c.pyapi.ulong, _HEAPTYPE))
                with builder.if_then(builder.icmp_unsigned("==", heap, heap.type(0))):
                    # A float subclass defined in C (NumPy's float64): its float value,
                    # read as for a float, calling nothing.
                    builder.store(c.pyapi.float_as_double(obj), value)


_unbox(PlainFloat)(_unbox_plain_float)


def _plain_value_typing(typingctx: Any, x: Any) -> Any:
    """float64 of a :data:`PLAIN_FLOAT` (or float64) argument: the same 64 bits."""
    if not isinstance(x, PlainFloat) and x != types.float64:
        return None
    sig = types.float64(x)

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        return args[0]

    return sig, codegen


plain_value: Any = _intrinsic(_plain_value_typing)
