"""PlanarFusion's compiled paths: one filter body, one signature per kernel, fast = general.

Issue 17 cut the first use with an empty numba cache from about 16 s to about
4.5 s of CPU: the filter is one function, the step (``_planar_step``), which
the online entries and the batch loop call, kernels copy arrays with loops instead of slice
assignment, and the public layer always passes the same types. These tests
keep those properties; they never time anything.
"""

from __future__ import annotations

import ast
import inspect
import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kernel_signatures import compiled_signatures
from navkit._shared.jit import jit_disabled
from navkit.errors import FilterError
from navkit.estimation import MeasurementLog, PlanarFusion, UpdateResult
from navkit.estimation import _fusion_kernels as kernels

#: Every online kind, predict, the general path (a numpy scalar) and the batch, as
#: the source of a fresh process (see test_every_kernel_is_compiled_for_one_signature).
_EVERY_PATH = """
import numpy as np
from navkit.estimation import MeasurementLog, PlanarFusion
fusion = PlanarFusion(gate_probability=0.99)
fusion.update_odometry(0.01, 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4)
fusion.update_speed(0.02, 1.0, variance=1e-4)
fusion.update_yaw(0.03, 0.0, variance=1e-4)
fusion.update_yaw_rate(0.04, 0.1, variance=1e-4)
fusion.update_acceleration(0.05, 0.0, variance=1e-4)
fusion.predict(0.06)
fusion.update_yaw(np.float64(0.07), 0.0, variance=1e-4)
t = np.linspace(0.1, 0.5, 5)
fusion.update_batch(MeasurementLog.from_streams(odometry=(t, np.ones(5), np.zeros(5))))
PlanarFusion().update_batch(MeasurementLog.from_streams(yaw=(t, np.zeros(5))))
"""


# Compiled signatures are what is counted: with the JIT disabled the kernels are
# plain functions, with none.
@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: plain functions")
def test_every_kernel_is_compiled_for_one_signature() -> None:
    """Each online kind, predict, the general path and the batch share the same kernels."""
    # In a fresh process: this one's kernels keep the signatures of every earlier
    # test's direct calls (planar_run given writable copies of a log's read-only
    # arrays, say), which ran before this test under another order or split of the
    # suite (xdist).
    compiled = compiled_signatures(_EVERY_PATH, ["navkit.estimation._fusion_kernels"])
    for kernel in ("_fusion_kernels.planar_step_plain", "_fusion_kernels.planar_run"):
        assert len(compiled.get(kernel, [])) == 1, (kernel, compiled)
    # The step's body (a helper) once at most: the batch loop calls it with int64 (not
    # literal) mode arguments, as the online entry does (none when both callers were
    # loaded from numba's cache).
    assert len(compiled.get("_fusion_kernels._planar_step", [])) <= 1, compiled


def test_the_batch_loop_calls_the_online_step() -> None:
    """The filter is compiled once: planar_run has no filter body of its own.

    Since review 51 it calls the online entry's compiled step by its address
    (``call_step``), so that the step is not linked into it a second time.
    """
    source = inspect.getsource(kernels.planar_run)
    assert "call_step(step," in source and "_cholesky_inplace" not in source
    for entry in (kernels.planar_step, kernels.planar_step_plain):  # thin entries
        assert "_planar_step(" in inspect.getsource(entry)
    assert not hasattr(kernels, "planar_row")


@pytest.mark.parametrize("t0", [None, 0.5])
def test_a_refused_online_step_is_undone_with_the_clock(t0: float | None) -> None:
    """TIME_GAP leaves x, P and the time as before (restored by undo_step)."""
    fusion = PlanarFusion(t0=t0)
    fusion.update_speed(1.0, 1.0, variance=1e-3)
    x, p, t = fusion.x, fusion.P, fusion.t
    for call in (
        lambda: fusion.predict(1e300),
        lambda: fusion.update_yaw(1e300, 0.0, variance=1e-3),
        lambda: fusion.update_yaw(np.float64(1e300), 0.0, variance=1e-3),  # type: ignore[arg-type]
    ):
        with pytest.raises(FilterError, match="time gap"):
            call()
        assert fusion.t == t
        assert np.array_equal(fusion.x, x) and np.array_equal(fusion.P, p)


def _slice_copies(tree: ast.AST) -> list[int]:
    """Lines assigning something other than a number to an array slice (``a[:] = b``)."""
    lines = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Assign) and not isinstance(node.value, ast.Constant):
            for target in node.targets:
                if isinstance(target, ast.Subscript) and any(
                    isinstance(part, ast.Slice) for part in ast.walk(target.slice)
                ):
                    lines.append(node.lineno)
    return lines


def test_kernels_copy_arrays_without_slice_assignment() -> None:
    """numba compiles ``a[:] = b`` with a formatted error path: 0.2-1.9 s per site."""
    assert _slice_copies(ast.parse(inspect.getsource(kernels))) == []
    assert _slice_copies(ast.parse("a[:, 1:] = b\nc[0] = d\ne[:] = 0.0")) == [1]


def _same(a: UpdateResult, b: UpdateResult) -> None:
    assert a.accepted == b.accepted and a.reason == b.reason
    assert np.array_equal(a.residual, b.residual)
    assert a.nis == b.nis or (math.isnan(a.nis) and math.isnan(b.nis))


_KINDS: dict[str, Callable[[PlanarFusion, Any, Any, Any], UpdateResult]] = {
    "speed": lambda f, t, z, var: f.update_speed(t, z, variance=var),
    "yaw": lambda f, t, z, var: f.update_yaw(t, z, variance=var),
    "yaw_rate": lambda f, t, z, var: f.update_yaw_rate(t, z, variance=var),
    "acceleration": lambda f, t, z, var: f.update_acceleration(t, z, variance=var),
    "odometry": lambda f, t, z, var: f.update_odometry(
        t, z, 0.5 * z, v_variance=var, omega_variance=2.0 * var
    ),
}


@settings(max_examples=30, deadline=None)
@given(
    steps=st.lists(
        st.tuples(
            st.sampled_from([*_KINDS, "predict"]),
            st.floats(-0.02, 0.2),
            st.floats(-4.0, 4.0) | st.just(1e300),
            st.floats(1e-6, 10.0),
        ),
        min_size=1,
        max_size=25,
    ),
    t0=st.none() | st.just(0.0),
    gate=st.none() | st.just(0.9),
)
def test_fast_path_equals_general_path_bit_for_bit(
    steps: list[tuple[str, float, float, float]], t0: float | None, gate: float | None
) -> None:
    """Plain floats (compiled checks) and numpy scalars (Python checks) give the same filter.

    Covers the first measurement without ``t0`` (it only sets the clock), out-of-order
    and gated measurements, overflowing values and predictions.
    """
    fast = PlanarFusion(t0=t0, gate_probability=gate)
    general = PlanarFusion(t0=t0, gate_probability=gate)
    t = 0.0
    for kind, dt, z, var in steps:
        t += dt
        if kind == "predict":
            outcomes = []
            for fusion, time in ((fast, t), (general, np.float64(t))):
                try:
                    fusion.predict(time)  # type: ignore[arg-type]
                    outcomes.append("ok")
                except ValueError as error:
                    outcomes.append(str(error))
            assert outcomes[0] == outcomes[1]
        else:
            update = _KINDS[kind]
            _same(update(fast, t, z, var), update(general, np.float64(t), np.float64(z), var))
        assert fast.t == general.t
        assert np.array_equal(fast.x, general.x) and np.array_equal(fast.P, general.P)


@pytest.mark.parametrize("kind", list(_KINDS))
def test_fast_path_refusals_raise_and_leave_the_filter(kind: str) -> None:
    """Arguments the compiled step refuses take the general way: same errors as documented."""
    fusion = PlanarFusion(t0=1.0)
    update = _KINDS[kind]
    update(fusion, 1.5, 0.2, 1e-3)
    x, p = fusion.x, fusion.P
    name = {"speed": "v", "odometry": "v", "yaw": "yaw", "yaw_rate": "omega"}.get(kind, "a")
    for t, z, var, error, match in (
        (math.nan, 0.0, 1e-3, ValueError, "^t "),
        (2.0, math.inf, 1e-3, ValueError, f"^{name} "),
        (2.0, 0.0, 0.0, ValueError, "variance"),
        (2.0, 0.0, 1e101, ValueError, "variance"),
        (2.0, True, 1e-3, TypeError, f"^{name} "),
    ):
        with pytest.raises(error, match=match):
            update(fusion, t, z, var)
    with pytest.raises(FilterError, match="time gap"):
        update(fusion, 1e300, 0.0, 1e-3)
    assert fusion.t == 1.5
    assert np.array_equal(fusion.x, x) and np.array_equal(fusion.P, p)
    assert update(fusion, 1.0, 0.0, 1e-3).reason.startswith("out of order")  # type: ignore[union-attr]
    assert fusion.t == 1.5


def test_clock_lives_in_the_buffer_and_batch_continues_it() -> None:
    """predict, the online updates and update_batch share one filter time."""
    fusion = PlanarFusion()
    assert fusion.t is None and "t=None" in repr(fusion)
    fusion.predict(2.0)  # before any measurement: only sets the clock
    assert fusion.t == 2.0 and np.array_equal(fusion.x, np.zeros(6))
    log = MeasurementLog.from_streams(yaw=([1.0, 3.0, 4.0], [0.0, 0.1, 0.2]))
    result = fusion.update_batch(log)
    assert result.status.tolist() == [3, 0, 0]  # the row at 1 s is older than the clock
    assert fusion.t == 4.0
    assert not fusion.update_yaw(3.5, 0.0, variance=1e-3).accepted
