"""``min`` and ``max`` of two numbers for kernels, without compiling an overload (private).

Imports numba: kernel modules bind :func:`min2` and :func:`max2` lazily with
:func:`navkit._shared.jit.bind_numba_names` (importing them must not import
numba), with Python's ``min`` and ``max`` for ``NUMBA_DISABLE_JIT``.

numba compiles the ``min`` and ``max`` builtins as overloads of their own,
each a numba function compiled once per argument types and process (issue 17:
0.02-0.04 s each; a first ``Simulation.run`` compiled five). A conditional
expression written out instead (``b if b > a else a``) compiles nothing more,
but numba lowers it as control flow that LLVM keeps as a compare and branch
(measured in the simulator's clearance and LiDAR kernels, review 50), where
the builtin is one select (``maxsd``, ``cmov``): unpredictable comparisons in
hot loops would pay for mispredicted branches. These intrinsics emit the
builtin's own code in place (numba's ``do_minmax``: both arguments cast to
their unified type, then ``b > a`` or ``b < a`` and a select), so they give
the builtin's results bit for bit (NaN and signed zeros included: the first
argument is kept unless the second compares greater, or smaller) and the same
machine code, without a function to compile. Two arguments only: nest them
for more, as the builtin reduces them (``max(a, b, c)`` is
``max2(max2(a, b), c)``). With numba's JIT disabled they are Python's ``min``
and ``max``.

numba caches a kernel keyed on its own file only, and these intrinsics'
code is built into the kernels that call them: a change here that changes
their code must also change every kernel file that calls them (a comment
will do), or machine code cached before it stays in use.

Examples
--------
>>> import numba
>>> from navkit._shared.selects import max2, min2
>>> clamp = numba.njit(lambda x: min2(max2(x, 0.0), 1.0))
>>> clamp(1.5), clamp(-0.5), clamp(0.25)
(1.0, 0.0, 0.25)
"""

from __future__ import annotations

import operator
from collections.abc import Callable
from typing import Any

from numba.core import types
from numba.core.extending import intrinsic
from numba.cpython import builtins

from navkit._shared.jit import jit_disabled

__all__ = ["max2", "min2"]

_NUMBERS = (types.Number, types.Boolean)


def _select(context: Any, builder: Any, argtys: list[Any], args: list[Any], compare: Any) -> Any:
    """``b`` if ``compare(b, a)`` else ``a``, both cast to their unified type.

    The code numba's ``do_minmax`` emits for two arguments, spelt out here
    for a numba without that private function (it is not public API: a
    rename would otherwise make every kernel module fail to import).
    """
    unified = context.typing_context.unify_types(*argtys)
    a, b = (context.cast(builder, v, t, unified) for v, t in zip(args, argtys, strict=True))
    compare_impl = context.get_function(compare, types.boolean(unified, unified))
    return builder.select(compare_impl(builder, (b, a)), b, a)


#: numba's code for its min and max builtins (Any: untyped in numba), or the
#: same code spelt out where numba has no ``do_minmax``.
_DO_MINMAX: Any = getattr(builtins, "do_minmax", _select)


def _typing(compare: Callable[[Any, Any], Any]) -> Callable[..., Any]:
    """The typing function of an intrinsic choosing by ``compare`` as numba's builtin does."""

    def typer(typingctx: Any, a: Any, b: Any) -> Any:
        if not (isinstance(a, _NUMBERS) and isinstance(b, _NUMBERS)):
            return None
        unified = typingctx.unify_types(a, b)
        if unified is None:
            return None

        def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
            return _DO_MINMAX(context, builder, list(signature.args), list(args), compare)

        return unified(a, b), codegen

    return typer


#: ``min(a, b)`` of two numbers in a kernel, as numba's builtin (the second if smaller).
min2: Any = intrinsic(_typing(operator.lt))
#: ``max(a, b)`` of two numbers in a kernel, as numba's builtin (the second if greater).
max2: Any = intrinsic(_typing(operator.gt))
if jit_disabled():
    # Kernels run as Python there (an intrinsic cannot be called from Python):
    # the builtins themselves, as the kernel modules bind them.
    min2 = min
    max2 = max
