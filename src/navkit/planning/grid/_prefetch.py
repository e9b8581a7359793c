"""A software prefetch for numba kernels (private; imports numba: bound lazily).

``prefetch(arr, i)`` in a kernel asks the CPU to bring the cache line holding
``arr[i]`` (a C-contiguous 1-d array) into every cache level: LLVM's
``llvm.prefetch`` intrinsic (read, high temporal locality, data cache; x86
``prefetcht0``). It is a hint: it never faults, computes nothing and returns
nothing, so ``i`` may lie outside the array (no bounds check; the address is
only formed, never read by the program). On a target without a prefetch
instruction LLVM drops the call when it lowers the intrinsic (its documented
behaviour: "if the target does not support prefetches, it is a no-op"), so
kernels using it stay correct everywhere. Works with numba 0.62 (llvmlite
0.45) and later.

Kernel modules bind it with :func:`navkit._shared.jit.bind_numba_names`
(importing them must not import numba: this module imports numba and
llvmlite at the top), with a Python no-op for ``NUMBA_DISABLE_JIT=1``.
"""

from __future__ import annotations

from typing import Any

from llvmlite import ir  # type: ignore[import-untyped]
from numba.core import types
from numba.extending import intrinsic


def _prefetch_typing(typingctx: Any, arr: Any, idx: Any) -> Any:
    """Prefetch the cache line of ``arr[idx]`` for reading (no bounds check, no fault)."""
    sig = types.void(arr, idx)

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        array = context.make_array(signature.args[0])(context, builder, args[0])
        address = builder.gep(array.data, [args[1]], inbounds=False)
        byte_ptr = ir.IntType(8).as_pointer()
        i32 = ir.IntType(32)
        fnty = ir.FunctionType(ir.VoidType(), [byte_ptr, i32, i32, i32])
        fn = builder.module.declare_intrinsic("llvm.prefetch", [byte_ptr], fnty)
        # Arguments: read (0), high temporal locality (3), data cache (1).
        builder.call(fn, [builder.bitcast(address, byte_ptr), i32(0), i32(3), i32(1)])
        return context.get_dummy_value()

    return sig, codegen


# Not a decorator: numba 0.62's intrinsic is untyped (mypy --strict refuses the
# decorated function there).
prefetch: Any = intrinsic(_prefetch_typing)
