"""The batch loop's call of the step by its address keeps the step's exception (review 51, FRESH2).

``planar_run`` calls the online entry's compiled ``_planar_step`` through
:func:`navkit.estimation._step_call.call_step` (review 51, FUSIONCOLD). That
call dropped numba's status of the callee: a step that raised left its result
unwritten, and the loop read it as a status and NIS. Today's step raises
nowhere reachable, so a stand-in step with the same signature raises here:
the exception reaches the caller, and a step that returns is read as before.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit._shared.jit import jit_disabled

pytestmark = pytest.mark.skipif(
    jit_disabled(), reason="NUMBA_DISABLE_JIT=1: no compiled step, no address"
)


def _kernels() -> tuple[object, object, object]:
    """A step that raises when ``count`` is 7, a kernel giving its address, one calling it."""
    from numba import njit

    from navkit.estimation._step_call import call_step, step_pointer

    @njit
    def step(buf, t, first, count, z0, z1, var0, var1, gate):  # type: ignore[no-untyped-def]
        if count == 7:
            raise ValueError("the stand-in step raised")
        buf[0] = z0 + t
        return 3 + first, z0 * 2.0

    @njit
    def address():  # type: ignore[no-untyped-def]
        return step_pointer(step)

    @njit
    def call(step_address, buf, count):  # type: ignore[no-untyped-def]
        status, nis = call_step(step_address, buf, 0.5, 2, count, 1.25, 0.0, 0.0, 0.0, 0.0)
        return status, nis

    return step, address, call


def test_a_step_that_raises_raises_in_its_caller() -> None:
    """The stand-in's ValueError reaches Python (before: an unwritten result was returned)."""
    _, address, call = _kernels()
    buf = np.zeros(4)
    with pytest.raises(ValueError, match="the stand-in step raised"):
        call(address(), buf, 7)  # type: ignore[operator]
    assert buf[0] == 0.0


def test_a_step_that_returns_is_read_as_before() -> None:
    """Status, NIS and the buffer write come back through the address unchanged."""
    _, address, call = _kernels()
    buf = np.zeros(4)
    assert call(address(), buf, 1) == (5, 2.5)  # type: ignore[operator]
    assert buf[0] == 1.75


def test_a_step_with_another_result_is_refused_or_converted() -> None:
    """A step returning a float status: numba refuses it or converts it, never misreads it.

    numba 0.62 did not check the result of the step it compiled for the
    pointer, and the call read the float's bits as an int (4616752568008179712
    for 4.5); later versions convert the result to the declared one.
    """
    from numba import njit
    from numba.core.errors import TypingError

    from navkit.estimation._step_call import call_step, step_pointer

    @njit
    def step(buf, t, first, count, z0, z1, var0, var1, gate):  # type: ignore[no-untyped-def]
        return 1.5 * count, z0

    @njit
    def address():  # type: ignore[no-untyped-def]
        return step_pointer(step)

    @njit
    def call(step_address, buf):  # type: ignore[no-untyped-def]
        return call_step(step_address, buf, 0.5, 2, 3, 1.25, 0.0, 0.0, 0.0, 0.0)

    try:
        pointer = address()
    except TypingError as exc:
        assert "the step returns" in str(exc)
        return
    assert call(pointer, np.zeros(4)) == (4, 1.25)  # 4.5 converted as numba converts
