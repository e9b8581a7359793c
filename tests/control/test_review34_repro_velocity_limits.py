"""``limit_velocity_change`` gives the same bits on every CPU (review 34).

It measured the change with ``np.linalg.norm`` and ``np.dot``, OpenBLAS's
``ddot``, whose kernel is chosen for the CPU: on a recent Intel Xeon (AVX-512)
its fused multiply-adds gave other last bits than the kernels of older CPUs
(Haswell, Zen, Sandy Bridge), which add the rounded products in order, so the
``omni-apf`` and ``soccer`` scenarios (and ``PotentialFieldController``) ran a
slightly different robot on each machine. The products are now added in order:
the older CPUs' bits, everywhere.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from navkit.control import limit_velocity_change
from openblas_kernels import core_types
from subprocess_probe import probe_outcome


def _oracle(
    prev: np.ndarray, want: np.ndarray, accel: float, decel: float, dt: float
) -> np.ndarray:
    # The rule of the docstring with every dot product added in order, in Python floats.
    delta = want - prev
    n = math.sqrt(sum((float(d) * float(d) for d in delta), 0.0))
    if n == 0.0:
        return prev.copy()
    u = delta / n
    t_slow = max(0.0, -2.0 * sum((float(p) * float(q) for p, q in zip(prev, u, strict=True)), 0.0))
    if n <= t_slow:
        t = min(n, decel * dt)
    elif accel * dt > t_slow:
        t = min(n, accel * dt)
    else:
        t = min(t_slow, decel * dt)
    return prev + t * u


@pytest.mark.parametrize("k", [2, 3, 5])
def test_the_limit_is_the_in_order_rule_bit_for_bit(k: int) -> None:
    rng = np.random.default_rng(k)
    prev = rng.normal(size=(2000, k))
    want = prev + rng.normal(size=(2000, k)) * rng.choice([0.01, 0.1, 1.0], size=(2000, 1))
    pairs = list(zip(prev, want, strict=True))
    got = np.array(
        [limit_velocity_change(p, w, max_accel=0.5, max_decel=0.8, dt=0.1) for p, w in pairs]
    )
    expected = np.array([_oracle(p, w, 0.5, 0.8, 0.1) for p, w in pairs])
    np.testing.assert_array_equal(got, expected)


_PROBE = """
import hashlib, json
import numpy as np
from navkit.control import limit_velocity_change
rng = np.random.default_rng(11)
out = []
for k in (2, 3):
    prev = rng.normal(size=(500, k)); want = prev + rng.normal(size=(500, k)) * 0.2
    for p, w in zip(prev, want):
        out.append(limit_velocity_change(p, w, max_accel=0.5, max_decel=0.8, dt=0.1))
print(json.dumps(hashlib.sha256(np.concatenate(out).tobytes()).hexdigest()))
"""


@pytest.mark.slow
def test_the_same_limits_under_every_openblas_kernel(monkeypatch: pytest.MonkeyPatch) -> None:
    digests = {}
    for core in core_types():
        monkeypatch.setenv("OPENBLAS_CORETYPE", core)
        digests[core] = probe_outcome(_PROBE)
    assert len(set(digests.values())) == 1, json.dumps(digests)
