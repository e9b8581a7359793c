"""The batch loop runs the online entry's compiled step by its address (review 51, FUSIONCOLD).

numba linked the fusion step ``_planar_step`` into both of its callers, the
online entry ``planar_step_plain`` and the batch loop ``planar_run``, where LLVM
optimised it and made its machine code twice (issue 17: about 0.3 s of a first
``PlanarFusion`` use). ``planar_run`` now calls the online entry's function
through the address :func:`step_address` finds, so the step's code is in one
library. These tests check that structure (on the compiled code, in a fresh
process) and that the batch still fuses exactly as the online updates do.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from navkit._shared.jit import jit_disabled
from navkit.estimation import MeasurementLog, PlanarFusion
from navkit.estimation import _fusion_kernels as kernels
from subprocess_probe import cold_outcome

# A fresh process with an empty cache of its own: which functions the batch loop's
# and the online entry's libraries define (LLVM IR after linking), and the batch's states.
_PROBE = """
import json
import numpy as np
from navkit.estimation import MeasurementLog, PlanarFusion
from navkit.estimation import _fusion_kernels as k
t = np.linspace(0.0, 0.4, 5)
log = MeasurementLog.from_streams(odometry=(t, np.ones(5), np.zeros(5)), yaw=(t, np.zeros(5)))
states = PlanarFusion().update_batch(log).states
PlanarFusion().update_odometry(0.02, 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4)


def defined(dispatcher):
    (compiled,) = dispatcher.overloads.values()
    return [line.split("@", 1)[1].split("(", 1)[0] for line in
            compiled.library.get_llvm_str().splitlines() if line.startswith("define")]


print(json.dumps({"run": defined(k.planar_run), "plain": defined(k.planar_step_plain),
                  "states": states.tolist()}))
"""


@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: nothing is compiled")
def test_the_step_is_compiled_into_the_online_entry_only() -> None:
    """planar_run's library defines no copy of _planar_step; planar_step_plain's does."""
    outcome = cold_outcome(_PROBE)
    steps = {name: [f for f in outcome[name] if "_planar_step" in f] for name in ("run", "plain")}
    assert steps["run"] == [], steps  # before review 51: the linked copy
    assert len(steps["plain"]) == 1, steps
    # (The batch's states are those of this process, compiled or loaded.)
    t = np.linspace(0.0, 0.4, 5)
    log = MeasurementLog.from_streams(odometry=(t, np.ones(5), np.zeros(5)), yaw=(t, np.zeros(5)))
    assert np.array_equal(np.array(outcome["states"]), PlanarFusion().update_batch(log).states)


def test_the_address_is_found_once_per_process() -> None:
    """Every batch call passes the same address; 0 only with the JIT disabled."""
    address = kernels.step_address()
    assert kernels.step_address() == address
    assert (address == 0) == jit_disabled()


@pytest.mark.parametrize("gate", [None, 0.5])
def test_batch_equals_online_updates_bit_for_bit(gate: float | None) -> None:
    """Rows through the address give the online updates' states, covariances and NIS."""
    rng = np.random.default_rng(51)
    n = 60
    t = np.cumsum(rng.uniform(0.0, 0.05, n))
    v = 1.0 + 0.2 * rng.normal(size=n)
    w = 0.3 * rng.normal(size=n)
    yaw = np.mod(0.1 * t + 0.05 * rng.normal(size=n) + math.pi, 2 * math.pi) - math.pi
    log = MeasurementLog.from_streams(
        odometry=(t, v, w), odometry_variance=(1e-3, 1e-3),
        yaw=(t + 0.001, yaw), yaw_variance=1e-2,
    )  # fmt: skip
    kwargs = {} if gate is None else {"gate_probability": 1.0 - gate}
    batch = PlanarFusion(t0=0.0, **kwargs).update_batch(log)
    online = PlanarFusion(t0=0.0, **kwargs)
    order = np.argsort(np.concatenate([t, t + 0.001]), kind="stable")
    for row, i in enumerate(order):
        if i < n:
            result = online.update_odometry(
                float(t[i]), float(v[i]), float(w[i]), v_variance=1e-3, omega_variance=1e-3
            )
        else:
            result = online.update_yaw(float(t[i - n] + 0.001), float(yaw[i - n]), variance=1e-2)
        assert np.array_equal(batch.states[row], online.x), row
        assert np.array_equal(batch.covariances[row], online.P), row
        nis = batch.nis[row]
        assert nis == result.nis or (math.isnan(nis) and math.isnan(result.nis)), row
