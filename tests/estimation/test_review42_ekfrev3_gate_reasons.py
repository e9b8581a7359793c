"""Review 42 (EKFREV3): a gate's rejection reason reads the NIS above the gate.

The reason printed the NIS with ``:.6g`` and the gate as its repr: a NIS of
100.00000000000001 at a gate of 100 read "NIS 100 > 100.0", and one just above any
gate could read below it. Now 6 significant digits, or as many more as show it above.
"""

from __future__ import annotations

import math
import re
import sys
from pathlib import Path

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st

from navkit.estimation import ExtendedKalmanFilter

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from precise_updates import linear, precise_problem

_REASON = re.compile(r"rejected by the gate: NIS (at least )?(\S+) > (\S+)")


def _read(reason: str | None) -> tuple[float, float]:
    """The NIS and the gate as a rejection reason prints them."""
    assert reason is not None
    found = _REASON.fullmatch(reason)
    assert found is not None, reason
    return float(found[2]), float(found[3])


def test_a_nis_an_ulp_above_the_gate_reads_above_it() -> None:
    ekf = ExtendedKalmanFilter([0.0], [[1.0]])
    result = ekf.update([math.sqrt(200.0)], linear(np.eye(1)), np.eye(1), np.eye(1), gate=100.0)
    assert not result.accepted and result.nis == math.nextafter(100.0, math.inf)
    # Before: "rejected by the gate: NIS 100 > 100.0".
    assert result.reason == "rejected by the gate: NIS 100.00000000000001 > 100.0"


@settings(max_examples=200, deadline=None)
@given(
    z=st.floats(0.1, 1e6),
    variance=st.floats(1e-6, 1e6),
    below=st.integers(1, 2**20),
)
@example(z=10.0, variance=1.0, below=1)  # a NIS of 6 digits: printed as it was
def test_a_rejected_nis_reads_above_the_gate(z: float, variance: float, below: int) -> None:
    h, r = np.eye(1), np.array([[variance]])
    nis = ExtendedKalmanFilter([0.0], [[1.0]]).update([z], linear(h), h, r).nis
    gate = nis
    for _ in range(below):  # a gate `below` ulps under the NIS
        gate = math.nextafter(gate, 0.0)
    if gate < 2.0**-1022:
        return
    result = ExtendedKalmanFilter([0.0], [[1.0]]).update([z], linear(h), h, r, gate=gate)
    assert not result.accepted and result.nis == nis
    printed, printed_gate = _read(result.reason)
    assert printed_gate == gate and printed > gate
    if float(f"{nis:.6g}") > gate:  # six digits suffice: printed as before
        assert f"NIS {nis:.6g} > " in str(result.reason)


def test_a_lower_bound_just_above_the_gate_reads_above_it() -> None:
    # Review 41's dense R of 26 components, computed S singular, one reading far off:
    # rejected on a lower bound of its exact NIS ("at least"), the gate an ulp below it.
    x0, p, h, r, z = precise_problem(24, (25, 30))  # type: ignore[misc]
    far = z.copy()
    far[0] += 100.0 * math.sqrt(float((h @ p @ h.T + r)[0, 0]))
    bound = ExtendedKalmanFilter(x0, p).update(far, linear(h), h, r, gate=1000.0).nis
    gate = math.nextafter(bound, 0.0)
    result = ExtendedKalmanFilter(x0, p).update(far, linear(h), h, r, gate=gate)
    assert not result.accepted and result.nis == bound
    assert result.reason is not None and "NIS at least" in result.reason
    printed, printed_gate = _read(result.reason)
    assert printed_gate == gate and printed > gate
