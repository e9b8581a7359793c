"""The fusion filter's batch loop calls the online step's machine code by its address (private).

Imports numba: :mod:`navkit.estimation._fusion_kernels` binds :func:`call_step`
when numba loads (importing a kernel module must not import numba).

numba links a copy of every kernel a kernel calls into the caller's code
library, where LLVM optimises it and makes its machine code again. The
filter's step, ``_planar_step``, the largest function of the filter, was thus
optimised and translated twice with an empty cache: linked into the online
entry ``planar_step_plain`` and into the batch loop ``planar_run``. The batch
loop now calls the step's function in the online entry's library through a
pointer its caller passes, so that the step is made once (issue 17:
about 0.3 s of the 2.4 s first use of ``PlanarFusion``; the call per row was a
call of the linked copy already, LLVM did not inline the step). The pointer is
that of the step's own function in the online entry's library, which the
entry returns when asked (:func:`step_pointer`): calling the entry instead
added a call per row, and the batch loop ran 8-10 % slower.

numba's cache keys a kernel on its own file, so the code these intrinsics make
is cached with ``_fusion_kernels.py``'s kernels: a change here (the calling
convention, :data:`STEP_ARGUMENTS`, :data:`STEP_RESULT`) must touch
``_fusion_kernels.py`` too, or a cached ``planar_run`` made before it is loaded
and calls the step the old way.
"""

from __future__ import annotations

from typing import Any

from llvmlite import ir  # type: ignore[import-untyped]
from numba import extending as _extending
from numba.core import cgutils as _cgutils
from numba.core import types
from numba.core.errors import TypingError as _TypingError

_intrinsic: Any = _extending.intrinsic
_if_unlikely: Any = _cgutils.if_unlikely  # (untyped in numba)

__all__ = ["STEP_ARGUMENTS", "STEP_RESULT", "call_step", "step_pointer"]

#: numba types of ``_planar_step``'s arguments, its one compiled signature.
STEP_ARGUMENTS: tuple[Any, ...] = (
    types.Array(types.float64, 1, "C"),  # buf
    types.float64,  # t
    types.int64,  # first
    types.int64,  # count
    *(types.float64,) * 5,  # z0, z1, var0, var1, gate
)
_Tuple: Any = types.Tuple  # (untyped in numba)
#: Its result: (status, nis).
STEP_RESULT: Any = _Tuple((types.int64, types.float64))


def _step_pointer_typing(typingctx: Any, step: Any) -> Any:
    """``step_pointer(_planar_step)``: the address (int64) of the step's compiled function.

    The function is the one linked into the calling kernel's library (as a call
    of the step links it), so the address is valid while that kernel's
    compiled code is, in this process.
    """
    if not isinstance(step, types.Dispatcher):
        return None
    compiled = step.dispatcher.get_compile_result(STEP_RESULT(*STEP_ARGUMENTS))
    # A TypingError, not a call of the wrong type, if the step's result changes: numba
    # 0.62's get_compile_result does not check it (the call read a float status's
    # bits as an int; review 51, FRESH2), later ones do or convert it.
    returned = compiled.signature.return_type
    if returned != STEP_RESULT:
        raise _TypingError(f"step_pointer: the step returns {returned}, not {STEP_RESULT}")
    sig = types.int64(step)

    def codegen(context: Any, builder: Any, signature: Any, values: Any) -> Any:
        function = context.declare_function(builder.module, compiled.fndesc)
        context.active_code_library.add_linking_library(compiled.library)
        return builder.ptrtoint(function, ir.IntType(64))

    return sig, codegen


def _call_step_typing(
    typingctx: Any, address: Any, buf: Any, t: Any, first: Any, count: Any,
    z0: Any, z1: Any, var0: Any, var1: Any, gate: Any,
) -> Any:  # fmt: skip
    """``call_step(address, buf, t, first, count, z0, z1, var0, var1, gate)``: (status, nis).

    ``address`` (int64) is that of the step's compiled function (numba's calling
    convention), which the caller got from
    ``navkit.estimation._fusion_kernels.step_address`` in this process; the
    rest are the step's arguments.
    """
    args = (buf, t, first, count, z0, z1, var0, var1, gate)
    if address != types.int64 or args != STEP_ARGUMENTS:
        return None
    sig = STEP_RESULT(address, *args)

    def codegen(context: Any, builder: Any, signature: Any, values: Any) -> Any:
        fnty = context.call_conv.get_function_type(STEP_RESULT, STEP_ARGUMENTS)
        step = builder.inttoptr(values[0], ir.PointerType(fnty))
        status, result = context.call_conv.call_function(
            builder, step, STEP_RESULT, STEP_ARGUMENTS, values[1:]
        )
        # As numba's own calls of a kernel do: the step's statuses are values and it
        # raises nowhere today, but a raise would leave the result unwritten, read as
        # a status and NIS (review 51, FRESH2).
        with _if_unlikely(builder, status.is_error):
            context.call_conv.return_status_propagate(builder, status)
        return result

    return sig, codegen


call_step: Any = _intrinsic(_call_step_typing)
step_pointer: Any = _intrinsic(_step_pointer_typing)
