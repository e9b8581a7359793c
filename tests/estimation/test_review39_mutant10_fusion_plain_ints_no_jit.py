"""With numba's JIT disabled, PlanarFusion refuses integer times beyond 2**53 as compiled.

Review 39 (mutation testing, MUTANT10). When the JIT is disabled the fusion
kernels run as Python, and ``_fusion_kernels._plain_value_python`` stands in for
the compiled ``plain_value``: an int of magnitude at most ``2**53`` is the fast
path's float, any other int NaN (the public layer's general path then refuses a
time float64 would round). ``_EXACT_INT`` raised to ``2**54`` passed every test: a
time of ``2**53 + 1`` was then fused as ``2**53`` without a word. Oracle: the
documented refusal (``update_speed``'s Raises: "an integer beyond 2**53"), the
same in the compiled filter (checked here in this process) as in the interpreted
one (a child process with ``NUMBA_DISABLE_JIT=1``).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from navkit.estimation import PlanarFusion

_TIMES = [2**53, -(2**53), 2**53 + 1, -(2**53) - 1, 2**53 + 2, 2**60]

_SCRIPT = r"""
import json, sys
from navkit.estimation import PlanarFusion
out = []
for t in json.loads(sys.argv[1]):
    f = PlanarFusion(t0=-2.0**61)
    try:
        f.update_speed(t, 1.0, variance=0.01)
        out.append(["fused", f.t])
    except ValueError as e:
        out.append(["ValueError", str(e).split(",")[0], f.t])
print(json.dumps(out))
"""


def _outcomes_here() -> list[list[object]]:
    out: list[list[object]] = []
    for t in _TIMES:
        f = PlanarFusion(t0=-(2.0**61))
        try:
            f.update_speed(t, 1.0, variance=0.01)
            out.append(["fused", f.t])
        except ValueError as e:
            out.append(["ValueError", str(e).split(",")[0], f.t])
    return out


def test_the_compiled_filter_refuses_integer_times_beyond_2_to_the_53() -> None:
    out = _outcomes_here()
    assert out[:2] == [["fused", 2.0**53], ["fused", -(2.0**53)]]
    for (kind, *rest), t in zip(out[2:], _TIMES[2:], strict=True):
        assert kind == "ValueError", t
        assert rest == ["t must be a time in seconds", -(2.0**61)], t


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX subprocess environment")
def test_the_interpreted_filter_refuses_them_as_the_compiled_one() -> None:
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_DISABLE_JIT")}
    env["NUMBA_DISABLE_JIT"] = "1"
    done = subprocess.run(
        [sys.executable, "-c", _SCRIPT, json.dumps(_TIMES)],
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    interpreted = json.loads(done.stdout.strip().splitlines()[-1])
    assert interpreted == _outcomes_here()
