"""``benchmarks/test_bench_cold_start.py --breakdown``: each CPU second counted once.

Runs the script's cheapest cold entry (``rollout``, two kernels) with an empty
numba cache in a subprocess and checks the breakdown's bookkeeping, not its
seconds: the phases add up to the call's CPU time, the compile phases are
found (numba's passes, LLVM's, the cache write) and the time is put on the
kernels compiled, not on their callers.
"""

from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

SCRIPT = Path(__file__).resolve().parents[1] / "benchmarks" / "test_bench_cold_start.py"


def _script() -> ModuleType:
    if not SCRIPT.is_file():
        pytest.skip("benchmarks/ is not part of this installation")
    pytest.importorskip("pytest_benchmark")
    spec = importlib.util.spec_from_file_location("navkit_bench_cold_start", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def result() -> dict[str, Any]:
    bench = _script()
    measured: dict[str, Any] = bench.measure("rollout", breakdown=True)
    return measured


def test_phases_add_up_to_the_cold_cpu(result: dict[str, Any]) -> None:
    phases = result["breakdown"]["phases"]
    assert math.isclose(sum(phases.values()), result["cold_cpu_s"], rel_tol=1e-9, abs_tol=1e-9)
    # What the instruments timed is most of it; "other" is the call's own Python.
    assert phases["other"] < 0.5 * result["cold_cpu_s"]
    for phase in ("numba pass nopython_type_inference", "numba pass native_lowering",
                  "LLVM function passes", "LLVM module passes", "LLVM machine code",
                  "cache write", "Python wrapper"):  # fmt: skip
        assert phases.get(phase, 0.0) > 0.0, phase
    assert all(secs >= -1e-3 for secs in phases.values()), phases


def test_time_goes_to_the_kernels_compiled(result: dict[str, Any]) -> None:
    kernels = result["breakdown"]["kernels"]
    assert math.isclose(
        sum(kernels.values()), sum(result["breakdown"]["phases"].values()) -
        result["breakdown"]["phases"]["other"], rel_tol=1e-6, abs_tol=1e-6,
    )  # fmt: skip
    rollout = "navkit.geometry._integrate_kernels.rollout_kernel"
    assert kernels[rollout] > 0.0
    # Its callee's compile is its own line, not counted in the caller's again.
    callees = [k for k in kernels if k.startswith("navkit.") and k != rollout]
    assert callees and all(kernels[k] > 0.0 for k in callees)


def test_plain_runs_have_no_breakdown() -> None:
    bench = _script()
    setup, timed = bench.ENTRIES["rollout"][:2]
    code = bench._CHILD.format(setup=setup, timed=timed, kernels=False, instrument="", report="")
    assert "_timed(" not in code and "_on_gc" not in code
