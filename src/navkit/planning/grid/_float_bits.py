"""The bits of a float64 as a uint64, for numba kernels (private; imports numba: bound lazily).

``f64_bits(x)`` in a kernel is ``np.float64(x).view(np.uint64)``: the IEEE 754
bit pattern of ``x``, an LLVM ``bitcast`` (no instruction on x86-64 beyond a
register move). A numba intrinsic rather than NumPy's scalar ``view``, which
numba types through the scalar's constructor and attribute on every first
use (about 0.03 s of compilation, where the intrinsic costs nothing
measurable): A*'s queue compares f by its bits (see
:mod:`navkit.planning.grid._search_heap`). ``f64_from_bits(b)`` is the
reverse, the float64 with the bits ``b``: jump point search queues f with
its lowest bits cleared as A* does, in float64 entries.

Kernel modules bind it with :func:`navkit._shared.jit.bind_numba_names`
(importing them must not import numba: this module imports numba and
llvmlite at the top), with NumPy's view for ``NUMBA_DISABLE_JIT=1``.
"""

from __future__ import annotations

from typing import Any

from llvmlite import ir  # type: ignore[import-untyped]
from numba.core import types
from numba.extending import intrinsic


def _f64_bits_typing(typingctx: Any, x: Any) -> Any:
    """The uint64 with the bits of the float64 ``x``."""
    if x != types.float64:
        return None
    sig = types.uint64(types.float64)

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        return builder.bitcast(args[0], ir.IntType(64))

    return sig, codegen


# Not a decorator: numba 0.62's intrinsic is untyped (mypy --strict refuses the
# decorated function there).
f64_bits: Any = intrinsic(_f64_bits_typing)


def _f64_from_bits_typing(typingctx: Any, x: Any) -> Any:
    """The float64 whose bits are the uint64 ``x`` (the inverse of :data:`f64_bits`)."""
    if x != types.uint64:
        return None
    sig = types.float64(types.uint64)

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        return builder.bitcast(args[0], ir.DoubleType())

    return sig, codegen


# ``f64_from_bits(f64_bits(x) & mask)`` clears bits of x: jump point search's
# queue keys f with A*'s band (``F_BAND`` in navkit.planning.grid._search_heap)
# in its float64 entries.
f64_from_bits: Any = intrinsic(_f64_from_bits_typing)
