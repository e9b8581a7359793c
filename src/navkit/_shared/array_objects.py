"""numba types for kernels that take any Python object as an argument (private).

Imports numba: kernel modules (:mod:`navkit.mapping._new_cells_kernel`,
:mod:`navkit.estimation._ekf_kernels`) bind the intrinsics below lazily
(importing them must not import numba).

A numba dispatcher types every argument of every call (``typeof``, then a
look-up of the compiled signature) and a public layer handing the user's
objects to a compiled entry directly would first have to test their types in
Python: either costs about 0.03-0.05 µs an array, a large part of issue 17's
small calls. The types and intrinsics here let one compiled entry, called
without the dispatcher, make those tests in C:

* :data:`OBJECT` is an argument type taking any object as it is (a borrowed
  reference: no conversion, no check, nothing that can fail);
* :func:`float_vector` and :func:`float_matrix` look at such an object's C
  struct: if it is an ``ndarray`` (exactly, no subclass) of native-order
  float64 with 1 (or 2) dimensions whose flags say C-contiguous, aligned and
  writeable (what numba's dispatcher types as a 1-D or 2-D writeable
  ``float64`` C array, the only type the general EKF's kernels were compiled
  for; the dispatcher would type an unaligned one so too, as ``numba.typeof``
  does not look at alignment, but the view's loads assume it: review 47
  refuses it, and the caller's general way copies it), they give
  ``True`` and a view of it (its data, shape and strides), else ``False`` and
  an empty view, having read nothing beyond the object's type unless that
  type is ``ndarray``; given a numba array of that type (a kernel compiled
  for arrays, typed by the dispatcher, where :data:`LAYOUT_OK` is False), they
  give ``True`` and the array;
* :func:`float_pairs` (``world_to_cell``'s points) likewise gives ``N`` and
  a view of an ``ndarray`` (exactly) of native-order float64 with shape
  ``(N, 2)`` and strides ``(16, 8)`` (C-contiguous; aligned or not, read-only
  or not: an unaligned C array, read only by the caller), else ``-1`` and an
  empty view;
* :func:`new_int_pairs` makes a new ``(N, 2)`` int64 ndarray with NumPy's own
  ``PyArray_Empty`` (what ``np.empty`` calls: the same array, flags and
  strides) and gives it as a :data:`NEW_OBJECT` with a view of its data;
* a :data:`NEW_OBJECT` return value becomes the array itself (its one
  reference passes to the caller), or ``None`` when null (:func:`no_object`;
  :func:`discard` releases an array first), or an exception when null with
  a Python error set (``PyArray_Empty`` out of memory: its ``MemoryError``).

Kernels using them must not release the GIL (they call the C API) and hold
the GIL from the entry's call to its return, as every navkit kernel without
``nogil`` does.

The struct offsets are NumPy's public ``PyArrayObject_fields`` and
``PyArray_Descr`` layouts after CPython's object header, unchanged since
NumPy 1.7 (NumPy 2 kept the fields read here where they were); they are
checked against a real array when this module is imported
(:data:`LAYOUT_OK`, which also requires NumPy 2, whose C-API table gives
``PyArray_Empty``), and if any differs :func:`float_pairs`,
:func:`float_vector` and :func:`float_matrix` refuse every object, so callers
take their general way (and ``PyArray_Empty`` is never called).
:data:`LAYOUT_OK` is read when a kernel is compiled and becomes part of its
machine code, which numba's cache does not key by: that is safe because
another NumPy major needs another numba, whose version numba checks before it
loads any cache; a test that fakes another NumPy (``np.__version__``) and
compiles a kernel with an :data:`OBJECT` argument must use a cache of its own.
The byte order is tested, not assumed: numba's dispatcher, once it has typed
an unaligned float64 array, types a big-endian one of the same ndim as native
float64 (its fingerprint of an array leaves the byte order out) and reads its
bytes swapped.

This module's path is written into users' numba cache indexes (each names the
module of its argument types) and numba unpickles an index before it checks
whether the index is stale: moving or renaming the module, or the type
classes, makes every cache written before fail to load with
``ModuleNotFoundError``/``AttributeError``; keep an alias where they were.
"""

from __future__ import annotations

import ctypes
import importlib
from typing import Any

import numpy as np
from llvmlite import binding as _binding  # type: ignore[import-untyped, unused-ignore]
from llvmlite import ir  # type: ignore[import-untyped, unused-ignore]
from numba import extending as _extending
from numba.core import cgutils as _cgutils
from numba.core import types
from numba.np import arrayobj as _arrayobj

# Any: numba's and llvmlite's code generation helpers are untyped.
cgutils: Any = _cgutils
binding: Any = _binding
arrayobj: Any = _arrayobj
NativeValue: Any = _extending.NativeValue
models: Any = _extending.models
_unbox: Any = _extending.unbox
_box: Any = _extending.box
_register_model: Any = _extending.register_model
_intrinsic: Any = _extending.intrinsic

__all__ = [
    "LAYOUT_OK",
    "NEW_OBJECT",
    "OBJECT",
    "discard",
    "float_matrix",
    "float_pairs",
    "float_vector",
    "is_null",
    "new_int_pairs",
    "no_object",
]

#: The float64 points :func:`float_pairs` gives: C-contiguous (N, 2), unaligned
#: (the same type as :func:`navkit.mapping._grid_kernels.world_to_cell_entry`'s).
POINTS = types.Array(types.float64, 2, "C", aligned=False)
#: The int64 cells :func:`new_int_pairs` gives: C-contiguous (N, 2).
CELLS = types.Array(types.int64, 2, "C")

_Tuple: Any = types.Tuple

# CPython's object header (ob_type is its last field), then NumPy's fields.
_HEAD = object.__basicsize__
_DATA = _HEAD  # PyArrayObject_fields.data
_NDIM = _HEAD + 8  # .nd (int)
_DIMS = _HEAD + 16  # .dimensions (npy_intp *)
_STRIDES = _HEAD + 24  # .strides (npy_intp *)
_DESCR = _HEAD + 40  # .descr (PyArray_Descr *)
_FLAGS = _HEAD + 48  # .flags (int)
_BYTEORDER = _HEAD + 10  # PyArray_Descr.byteorder (char)
_TYPE_NUM = _HEAD + 12  # PyArray_Descr.type_num (int)
_FLOAT64 = np.dtype(np.float64)
_NATIVE = ord("=")
# NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_ALIGNED | NPY_ARRAY_WRITEABLE: NumPy's
# NPY_ARRAY_CARRAY, the arrays the views' type (an aligned writeable C array)
# describes. numba's dispatcher would take an unaligned one for that type too
# (its typeof does not look), and the kernels' loads would assume an alignment
# its data lacks (review 47): it goes the caller's general way, a copy. This mask
# is compiled into the kernels using the views, whose cached machine code numba
# keys by their own source files only: change it together with those modules
# (estimation/_ekf_kernels.py changed in the same release as review 47), or
# caches made before keep the old test.
_BEHAVED_C = 0x0001 | 0x0100 | 0x0400

# Symbols the compiled code refers to by name (numba's cache stores code, not
# addresses): registered in every process before any kernel using them loads.
_ARRAY_EMPTY = "navkit_PyArray_Empty"
_NDARRAY_TYPE = "navkit_ndarray_type"
_INT64_DESCR = "navkit_int64_descr"
# PyArray_Empty's index in NumPy's C-API table (numpy/__multiarray_api.h,
# unchanged in NumPy 1 and 2: the table is NumPy's ABI).
_EMPTY_INDEX = 184


def _layout_ok() -> bool:
    """Whether the offsets above read a real float64 array's fields right."""
    points = np.empty((3, 2))
    at = id(points)
    descr = id(points.dtype)

    def pointer(address: int) -> int | None:
        return ctypes.c_void_p.from_address(address).value

    return bool(
        pointer(at + _HEAD - 8) == id(np.ndarray)
        and pointer(at + _DATA) == points.ctypes.data
        and ctypes.c_int.from_address(at + _NDIM).value == 2
        and ctypes.c_ssize_t.from_address(pointer(at + _DIMS) or 0).value == 3
        and ctypes.c_ssize_t.from_address((pointer(at + _STRIDES) or 0) + 8).value == 8
        and pointer(at + _DESCR) == descr
        and ctypes.c_int.from_address(descr + _TYPE_NUM).value == _FLOAT64.num
        and ctypes.c_char.from_address(descr + _BYTEORDER).value == b"="
        and ctypes.c_int.from_address(at + _FLAGS).value == points.flags.num
    )


#: Whether NumPy's structs are laid out as this module reads them (see the module),
#: in a NumPy 2 (whose C-API table, read by index below, is fixed for the major
#: version: a NumPy 3 takes the general way until checked).
LAYOUT_OK = np.lib.NumpyVersion(np.__version__).major == 2 and _layout_ok()


def _register_symbols() -> None:
    # A prototype of our own: setting restype and argtypes on
    # ctypes.pythonapi.PyCapsule_GetPointer would change them for every user of it.
    prototype = ctypes.PYFUNCTYPE(ctypes.c_void_p, ctypes.py_object, ctypes.c_char_p)
    get_pointer = prototype(("PyCapsule_GetPointer", ctypes.pythonapi))
    capsule = importlib.import_module("numpy._core._multiarray_umath")._ARRAY_API
    table = ctypes.cast(get_pointer(capsule, None), ctypes.POINTER(ctypes.c_void_p))
    binding.add_symbol(_ARRAY_EMPTY, table[_EMPTY_INDEX])
    binding.add_symbol(_NDARRAY_TYPE, id(np.ndarray))
    # The int64 descr lives as long as NumPy: PyArray_Empty takes a reference to it.
    binding.add_symbol(_INT64_DESCR, id(np.dtype(np.int64)))


_register_symbols()


class PyObjectArg(types.Type):  # type: ignore[misc, unused-ignore]  # (untyped in numba 0.62)
    """Any Python object, as a pointer to it (borrowed: the caller's tuple holds it)."""

    def __init__(self) -> None:
        super().__init__(name="navkit_object_arg")


class NewPyObject(types.Type):  # type: ignore[misc, unused-ignore]  # (untyped in numba 0.62)
    """A new reference to a Python object, or null (see the module)."""

    def __init__(self) -> None:
        super().__init__(name="navkit_new_object")


#: The argument type: any object, taken as it is.
OBJECT = PyObjectArg()
#: The return type: a new object, or null for None (or an error already set).
NEW_OBJECT = NewPyObject()

_BYTE_PTR = ir.IntType(8).as_pointer()
_I64 = ir.IntType(64)
_I32 = ir.IntType(32)


class _PointerModel(models.PrimitiveModel):  # type: ignore[misc]  # (a class of Any)
    """Stored as a pointer."""

    def __init__(self, dmm: Any, fe_type: Any) -> None:
        super().__init__(dmm, fe_type, _BYTE_PTR)


_register_model(PyObjectArg)(_PointerModel)
_register_model(NewPyObject)(_PointerModel)


def _unbox_object(typ: Any, obj: Any, c: Any) -> Any:
    """The object's pointer, borrowed, converting nothing."""
    return NativeValue(c.builder.bitcast(obj, _BYTE_PTR))


def _box_new_object(typ: Any, val: Any, c: Any) -> Any:
    """The object (its reference passes on); None for null, unless an error is set."""
    builder = c.builder
    obj = builder.bitcast(val, c.pyapi.pyobj)
    result = cgutils.alloca_once_value(builder, obj)
    # Null and no error: "not taken" (None). With an error set (MemoryError from
    # PyArray_Empty) the null is returned and the caller raises it. (The error
    # test is emitted inside the null branch: with's second item after the first.)
    with (
        builder.if_then(cgutils.is_null(builder, obj), likely=False),
        builder.if_then(cgutils.is_null(builder, c.pyapi.err_occurred())),
    ):
        builder.store(c.pyapi.make_none(), result)
    return builder.load(result)


_unbox(PyObjectArg)(_unbox_object)
_box(NewPyObject)(_box_new_object)


def _field(builder: Any, base: Any, offset: int, kind: Any) -> Any:
    """Load the ``kind`` at byte ``offset`` of the struct at integer address ``base``."""
    address = builder.add(base, _I64(offset))
    return builder.load(builder.inttoptr(address, kind.as_pointer()))


def _symbol(builder: Any, name: str) -> Any:
    """The address of a registered data symbol, as an integer."""
    module = builder.module
    try:
        variable = module.get_global(name)
    except KeyError:
        variable = ir.GlobalVariable(module, ir.IntType(8), name)
        variable.linkage = "external"
    return builder.ptrtoint(variable, _I64)


def _is_exact_ndarray(builder: Any, base: Any) -> Any:
    """Whether the object at integer address ``base`` is an ``ndarray`` (its type, no subclass)."""
    ob_type = _field(builder, base, _HEAD - 8, _I64)  # ob_type: the header's last field
    return builder.icmp_unsigned("==", ob_type, _symbol(builder, _NDARRAY_TYPE))


def _view(context: Any, builder: Any, kind: Any, data: Any, rows: Any) -> Any:
    """A numba array of type ``kind``, shape ``(rows, 2)``, over ``data`` (no owner)."""
    array = arrayobj.make_array(kind)(context, builder)
    intp = context.get_value_type(types.intp)
    itemsize = context.get_abi_sizeof(context.get_data_type(kind.dtype))
    arrayobj.populate_array(
        array,
        data=builder.bitcast(data, array.data.type),
        shape=[rows, intp(2)],
        strides=[intp(2 * itemsize), intp(itemsize)],
        itemsize=intp(itemsize),
        meminfo=None,
    )
    return array._getvalue()


def _float_pairs_typing(typingctx: Any, obj: Any) -> Any:
    """``(N, points)`` of an (N, 2) float64 C-contiguous ndarray, else ``(-1, empty)``."""
    if not isinstance(obj, PyObjectArg):
        return None
    sig = _Tuple((types.int64, POINTS))(obj)

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        rows = cgutils.alloca_once_value(builder, _I64(-1))
        data = cgutils.alloca_once_value(builder, _BYTE_PTR(None))
        base = builder.ptrtoint(args[0], _I64)
        if LAYOUT_OK:
            exact = _is_exact_ndarray(builder, base)
            # Nothing past the object header is read unless it is an ndarray.
            with builder.if_then(exact, likely=True):
                ndim = _field(builder, base, _NDIM, _I32)
                with builder.if_then(builder.icmp_signed("==", ndim, _I32(2)), likely=True):
                    dims = _field(builder, base, _DIMS, _I64.as_pointer())
                    strides = _field(builder, base, _STRIDES, _I64.as_pointer())
                    descr = _field(builder, base, _DESCR, _I64)
                    ok = builder.icmp_signed(
                        "==", builder.load(builder.gep(dims, [_I32(1)])), _I64(2)
                    )
                    for k, want in ((0, 16), (1, 8)):
                        stride = builder.load(builder.gep(strides, [_I32(k)]))
                        ok = builder.and_(ok, builder.icmp_signed("==", stride, _I64(want)))
                    type_num = _field(builder, descr, _TYPE_NUM, _I32)
                    order = _field(builder, descr, _BYTEORDER, ir.IntType(8))
                    ok = builder.and_(ok, builder.icmp_signed("==", type_num, _I32(_FLOAT64.num)))
                    ok = builder.and_(ok, builder.icmp_unsigned("==", order, order.type(_NATIVE)))
                    with builder.if_then(ok, likely=True):
                        builder.store(builder.load(dims), rows)
                        builder.store(_field(builder, base, _DATA, _BYTE_PTR), data)
        n = builder.load(rows)
        count = builder.select(builder.icmp_signed("<", n, _I64(0)), _I64(0), n)
        view = _view(context, builder, POINTS, builder.load(data), count)
        return context.make_tuple(builder, signature.return_type, [n, view])

    return sig, codegen


def _new_int_pairs_typing(typingctx: Any, rows: Any) -> Any:
    """A new (N, 2) int64 ndarray (:data:`NEW_OBJECT`, null if out of memory), its view."""
    if rows != types.int64:
        return None
    sig = _Tuple((NEW_OBJECT, CELLS))(rows)

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        pyapi = context.get_python_api(builder)
        empty = cgutils.get_or_insert_function(
            builder.module,
            ir.FunctionType(_BYTE_PTR, [_I32, _I64.as_pointer(), _BYTE_PTR, _I32]),
            _ARRAY_EMPTY,
        )
        descr = builder.inttoptr(_symbol(builder, _INT64_DESCR), _BYTE_PTR)
        pyapi.incref(builder.bitcast(descr, pyapi.pyobj))  # PyArray_Empty steals one
        dims = cgutils.alloca_once(builder, _I64, size=2)
        builder.store(args[0], dims)
        builder.store(_I64(2), builder.gep(dims, [_I32(1)]))
        obj = builder.call(empty, [_I32(2), dims, descr, _I32(0)])  # 0: C order
        data = cgutils.alloca_once_value(builder, _BYTE_PTR(None))
        missing = cgutils.is_null(builder, obj)
        with builder.if_then(builder.not_(missing), likely=True):
            builder.store(_field(builder, builder.ptrtoint(obj, _I64), _DATA, _BYTE_PTR), data)
        count = builder.select(missing, _I64(0), args[0])
        view = _view(context, builder, CELLS, builder.load(data), count)
        return context.make_tuple(builder, signature.return_type, [obj, view])

    return sig, codegen


def _is_null_typing(typingctx: Any, obj: Any) -> Any:
    """Whether a :data:`NEW_OBJECT` is null."""
    if not isinstance(obj, NewPyObject):
        return None

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        return cgutils.is_null(builder, args[0])

    return types.boolean(obj), codegen


def _discard_typing(typingctx: Any, obj: Any) -> Any:
    """Release a non-null :data:`NEW_OBJECT`; a null one (None) to return instead."""
    if not isinstance(obj, NewPyObject):
        return None

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        pyapi = context.get_python_api(builder)
        pyapi.decref(builder.bitcast(args[0], pyapi.pyobj))
        return _BYTE_PTR(None)

    return NEW_OBJECT(obj), codegen


def _no_object_typing(typingctx: Any) -> Any:
    """A null :data:`NEW_OBJECT`: the entry returns None."""

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        return _BYTE_PTR(None)

    return NEW_OBJECT(), codegen


def _itself(context: Any, builder: Any, signature: Any, args: Any) -> Any:
    """``(True, the array)``: :func:`float_vector` or :func:`float_matrix` of a typed array."""
    return context.make_tuple(builder, signature.return_type, [cgutils.true_bit, args[0]])


def _float_view_typing(ndim: int) -> Any:
    """The typing of :func:`float_vector` (``ndim`` 1) or :func:`float_matrix` (2)."""
    kind = types.Array(types.float64, ndim, "C")

    def typing(typingctx: Any, obj: Any) -> Any:
        if obj == kind:  # an array typed by numba's dispatcher (see LAYOUT_OK): itself
            return _Tuple((types.boolean, kind))(obj), _itself
        if not isinstance(obj, PyObjectArg):
            return None
        sig = _Tuple((types.boolean, kind))(obj)

        def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
            ok = cgutils.alloca_once_value(builder, ir.IntType(1)(0))
            data = cgutils.alloca_once_value(builder, _BYTE_PTR(None))
            shape = [cgutils.alloca_once_value(builder, _I64(0)) for _ in range(ndim)]
            strides = [cgutils.alloca_once_value(builder, _I64(0)) for _ in range(ndim)]
            base = builder.ptrtoint(args[0], _I64)
            if LAYOUT_OK:
                exact = _is_exact_ndarray(builder, base)
                # Nothing past the object header is read unless it is an ndarray.
                with builder.if_then(exact, likely=True):
                    nd = _field(builder, base, _NDIM, _I32)
                    flags = _field(builder, base, _FLAGS, _I32)
                    behaved = builder.icmp_signed(
                        "==", builder.and_(flags, _I32(_BEHAVED_C)), _I32(_BEHAVED_C)
                    )
                    right = builder.and_(builder.icmp_signed("==", nd, _I32(ndim)), behaved)
                    with builder.if_then(right, likely=True):
                        descr = _field(builder, base, _DESCR, _I64)
                        type_num = _field(builder, descr, _TYPE_NUM, _I32)
                        order = _field(builder, descr, _BYTEORDER, ir.IntType(8))
                        native = builder.and_(
                            builder.icmp_signed("==", type_num, _I32(_FLOAT64.num)),
                            builder.icmp_unsigned("==", order, order.type(_NATIVE)),
                        )
                        with builder.if_then(native, likely=True):
                            builder.store(ir.IntType(1)(1), ok)
                            builder.store(_field(builder, base, _DATA, _BYTE_PTR), data)
                            dims = _field(builder, base, _DIMS, _I64.as_pointer())
                            steps = _field(builder, base, _STRIDES, _I64.as_pointer())
                            for k in range(ndim):
                                builder.store(builder.load(builder.gep(dims, [_I32(k)])), shape[k])
                                builder.store(
                                    builder.load(builder.gep(steps, [_I32(k)])), strides[k]
                                )
            array = arrayobj.make_array(kind)(context, builder)
            intp = context.get_value_type(types.intp)
            arrayobj.populate_array(
                array,
                data=builder.bitcast(builder.load(data), array.data.type),
                shape=[builder.load(v) for v in shape],
                strides=[builder.load(v) for v in strides],
                itemsize=intp(8),
                meminfo=None,
            )
            return context.make_tuple(
                builder, signature.return_type, [builder.load(ok), array._getvalue()]
            )

        return sig, codegen

    typing.__name__ = typing.__qualname__ = ("float_vector", "float_matrix")[ndim - 1]
    return typing


float_pairs: Any = _intrinsic(_float_pairs_typing)
#: ``(ok, view)`` of an :data:`OBJECT`: see the module.
float_vector: Any = _intrinsic(_float_view_typing(1))
#: ``(ok, view)`` of an :data:`OBJECT`: see the module.
float_matrix: Any = _intrinsic(_float_view_typing(2))
new_int_pairs: Any = _intrinsic(_new_int_pairs_typing)
is_null: Any = _intrinsic(_is_null_typing)
discard: Any = _intrinsic(_discard_typing)
no_object: Any = _intrinsic(_no_object_typing)
