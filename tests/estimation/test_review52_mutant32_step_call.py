"""The fusion step's call by address takes only the step's own argument types (review 52, MUTANT32).

:func:`navkit.estimation._step_call.call_step` calls a compiled function
through a pointer, with numba's calling convention of ``_planar_step``'s one
signature (``STEP_ARGUMENTS``). A call with any other types must be refused
at typing: lowered, the values would be passed as the wrong machine types.
The mutation review found no test of that refusal (an ``and`` for the ``or``
of the check typed such a call, which numba failed to lower), nor of
``step_address``'s documented 0 with the JIT disabled, where the batch loop
calls the step as Python.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from navkit._shared.jit import jit_disabled
from subprocess_probe import jit_outcome

_COMPILED = pytest.mark.skipif(
    jit_disabled(), reason="NUMBA_DISABLE_JIT=1: no compiled step, no address"
)


def _caller(kind: str) -> object:
    """A kernel calling ``call_step`` with one argument of another type than the step's."""
    from numba import njit

    from navkit.estimation._step_call import call_step

    if kind == "float32 buffer":

        @njit
        def call(address, buf):  # type: ignore[no-untyped-def]
            return call_step(address, buf.astype(np.float32), 0.5, 2, 3, 1.25, 0.0, 0.0, 0.0, 0.0)

    elif kind == "float count":

        @njit
        def call(address, buf):  # type: ignore[no-untyped-def]
            return call_step(address, buf, 0.5, 2, 3.0, 1.25, 0.0, 0.0, 0.0, 0.0)

    else:  # a float address

        @njit
        def call(address, buf):  # type: ignore[no-untyped-def]
            return call_step(float(address), buf, 0.5, 2, 3, 1.25, 0.0, 0.0, 0.0, 0.0)

    return call


@_COMPILED
@pytest.mark.parametrize("kind", ["float32 buffer", "float count", "float address"])
def test_a_call_with_other_argument_types_is_refused_at_typing(kind: str) -> None:
    from numba.core.errors import TypingError

    call = _caller(kind)
    with pytest.raises(TypingError, match="call_step"):
        call(0, np.zeros(4))  # type: ignore[operator]


def test_no_address_with_the_jit_disabled_and_the_batch_fuses_as_python() -> None:
    out = jit_outcome(
        """
import json
import numpy as np
from navkit.estimation import MeasurementLog, PlanarFusion
from navkit.estimation import _fusion_kernels as k
t = np.linspace(0.0, 0.4, 5)
log = MeasurementLog.from_streams(odometry=(t, np.ones(5), np.zeros(5)), yaw=(t, np.zeros(5)))
states = PlanarFusion().update_batch(log).states
print(json.dumps({"address": k.step_address(), "x": states[-1].tolist()}))
""",
        disable_jit=True,
    )
    assert out["address"] == 0
    # The step run as Python fuses the log as the compiled one does.
    from navkit.estimation import MeasurementLog, PlanarFusion

    t = np.linspace(0.0, 0.4, 5)
    log = MeasurementLog.from_streams(odometry=(t, np.ones(5), np.zeros(5)), yaw=(t, np.zeros(5)))
    compiled = PlanarFusion().update_batch(log).states[-1]
    assert out["x"] == pytest.approx(compiled.tolist(), rel=1e-12, abs=1e-15)
