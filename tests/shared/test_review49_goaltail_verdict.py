"""Review 49 (GOALTAIL): the simulator's run kernels compile the goal test's ``hypot`` part only.

Compiled into the run kernels, ``navkit._shared.goal.at_goal``'s exact
arithmetic (Dekker's products, Shewchuk's Grow-Expansion, Rump's ulp) made
``Simulation.run``'s first use 2.9-3.1 s of CPU with a cold cache (issue 17:
at most 3 s). The kernels now compile :func:`goal_verdict` (``INSIDE``,
``OUTSIDE``, or ``UNDECIDED`` on a band 2**-48 wide around the tolerance's
circle) and leave an undecided step to ``at_goal`` in Python. Checked here
against rational arithmetic, in Python and compiled: a verdict is never wrong,
and the band is narrow (outside it nothing is left undecided, so that a run
does not stop for Python at every step); whole runs through the band:
``tests/sim/test_review49_goaltail_runs.py``.
"""

from __future__ import annotations

import math
import sys
from fractions import Fraction
from pathlib import Path

import numba
import numpy as np
import pytest

from navkit._shared.goal import (
    INSIDE,
    OUTSIDE,
    UNDECIDED,
    at_goal,
    goal_verdict,
    goal_verdict_kernel,
)

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from goal_oracle import Case, boundary_cases, exact_at_goal, radius

_NEXT_UP = math.inf
_NEXT_DOWN = -math.inf


@numba.njit(cache=False)
def _kernel_verdicts(cases: np.ndarray, out: np.ndarray) -> None:
    for i in range(cases.shape[0]):
        out[i] = goal_verdict_kernel(
            cases[i, 0], cases[i, 1], cases[i, 2], cases[i, 3], cases[i, 4]
        )


def _verdicts(cases: list[Case]) -> list[tuple[int, int]]:
    """Each case's verdict in Python and compiled."""
    compiled = np.zeros(len(cases), dtype=np.int64)
    _kernel_verdicts(np.array(cases, dtype=np.float64).reshape(-1, 5), compiled)
    return [(goal_verdict(*case), int(c)) for case, c in zip(cases, compiled, strict=True)]


def _relative_gap(case: Case) -> Fraction | None:
    """``|r² - R²| / R²`` for the offset's length ``r`` and the radius ``R`` at_goal
    compares with, exactly (None for a NaN offset)."""
    px, py, gx, gy, tolerance = case
    dx, dy = gx - px, gy - py
    if math.isnan(dx) or math.isnan(dy):
        return None
    big = radius(gx, gy, tolerance) ** 2
    return abs(Fraction(dx) ** 2 + Fraction(dy) ** 2 - big) / big


def _steps(x: float, toward: float, n: int) -> list[float]:
    """``x`` and its ``n`` float neighbours toward ``toward``."""
    out = [x]
    for _ in range(n):
        out.append(math.nextafter(out[-1], toward))
    return out


def _edge_cases() -> list[Case]:
    """Offsets where the verdict's own bounds fall: lengths within ulps of
    ``(1 -+ 2**-48)`` times the radius and of the radius itself, along an axis
    (hypot exact) and diagonal (hypot rounded), at tolerances from the least
    float to 1e300 m, goals near the origin, in UTM coordinates (where the
    goal's resolution exceeds a small tolerance) and near the largest float."""
    cases: list[Case] = []
    for t in (5e-324, 1e-310, 2.0**-960, 1e-280, 1e-12, 0.05, 0.1, 0.5, 3.0, 1e6, 1e300):
        for scale in (1.0 - 2.0**-48, 1.0, 1.0 + 2.0**-48, 1.0 - 2.0**-47, 1.0 + 2.0**-47):
            length = t * scale
            for d in _steps(length, _NEXT_DOWN, 3)[1:] + _steps(length, _NEXT_UP, 3):
                cases.append((0.0, 0.0, d, 0.0, t))  # along x: hypot is d itself
                cases.append((0.0, 0.0, 0.0, -d, t))
                side = d / math.sqrt(2.0)
                cases.append((1.0, -2.0, 1.0 + side, -2.0 + side, t))
                cases.append((0.0, 0.0, 0.6 * d, 0.8 * d, t))
    # The goal's resolution (2**-52 to 2**-53 times its finer coordinate) above the
    # tolerance: one, two and three ulps off, and 1e-6 m off (far: decided).
    for g in (4.6e6, 4.6e6 + 0.5, 2.0**52, 1e300, 1.7e308):
        for k in (1, 2, 3):
            off = _steps(g, _NEXT_DOWN, k)[-1]
            cases.append((off, g, g, g, 1e-12))
            cases.append((g, off, g, g, 0.75 * math.ulp(g)))
        cases.append((g - 1e-6 * g, g, g, g, 1e-12))
    return cases


def test_a_verdict_is_never_wrong_and_at_goal_is_exact() -> None:
    cases = boundary_cases(49, 3000) + _edge_cases()
    undecided = 0
    for case, (python, compiled) in zip(cases, _verdicts(cases), strict=True):
        want = exact_at_goal(*case)
        assert at_goal(*case) == want, case
        for verdict in (python, compiled):
            assert verdict in (INSIDE, OUTSIDE, UNDECIDED), case
            if verdict != UNDECIDED:
                assert (verdict == INSIDE) == want, (case, verdict)
        undecided += python == UNDECIDED
    # The cases reach the band: it is there that at_goal's exact arithmetic decides.
    assert undecided > 1000


def test_only_the_band_is_left_undecided() -> None:
    # Beyond 2**-45 (relative, of the squares) from the tolerance, hypot's few ulps
    # cannot matter: a verdict there, in Python and compiled, wherever the
    # tolerance is the radius (above the goal's resolution, and 2**-900 m).
    # (Undecided steps stop a run for Python: a band as wide as the tolerance would
    # stop it at every step near the goal.)
    cases = boundary_cases(49, 3000) + _edge_cases()
    rng = np.random.default_rng(49)
    for _ in range(2000):
        t = float(10.0 ** rng.uniform(-280.0, 280.0))
        scale = float(rng.choice([0.0, 1e-20, 0.5, 1.0 - 2.0**-40, 1.0 + 2.0**-40, 2.0, 1e20]))
        angle = float(rng.uniform(-math.pi, math.pi))
        gx, gy = (float(v) for v in rng.uniform(-10.0, 10.0, 2))
        cases.append((gx - t * scale * math.cos(angle), gy - t * scale * math.sin(angle),
                      gx, gy, t))  # fmt: skip
    decided = 0
    for case, verdicts in zip(cases, _verdicts(cases), strict=True):
        gap = _relative_gap(case)
        if gap is None:
            assert verdicts == (OUTSIDE, OUTSIDE), case  # a NaN offset, at once
        elif gap > Fraction(1, 2**45) and case[4] > max(
            2.0**-51 * min(abs(case[2]), abs(case[3])), 2.0**-900
        ):
            assert UNDECIDED not in verdicts, (case, verdicts)
            decided += 1
    assert decided > 2000


def test_a_robot_far_from_a_goal_below_its_resolution_is_decided() -> None:
    # A tolerance below the goal's resolution (1e-12 m at 4.6e6 m): the band is
    # around the resolution, not everywhere between the tolerance and it.
    g = 4.6e6
    for off in (3e-9, 1e-8, 1e-6, 1.0):  # 3 ulps and more
        assert goal_verdict(g - off, g, g, g, 1e-12) == OUTSIDE
    assert goal_verdict(g, g, g, g, 1e-12) == INSIDE
    # One ulp off is at the goal (review 38), left to at_goal: it is on the band.
    one = math.nextafter(g, 0.0)
    assert goal_verdict(one, g, g, g, 1e-12) == UNDECIDED
    assert at_goal(one, g, g, g, 1e-12)


class _Shifted:
    """``math`` with a ``hypot`` ``ulps`` floats above (or below) libm's: the
    verdict's margin is for a ``hypot`` a few ulps off, as some are."""

    def __init__(self, ulps: int) -> None:
        self.ulps = ulps

    def __getattr__(self, name: str) -> object:
        return getattr(math, name)

    def hypot(self, x: float, y: float) -> float:
        d = math.hypot(x, y)
        toward = _NEXT_UP if self.ulps > 0 else 0.0
        return _steps(d, toward, abs(self.ulps))[-1]


def test_the_verdict_holds_with_a_hypot_four_ulps_off(monkeypatch: pytest.MonkeyPatch) -> None:
    import navkit._shared.goal as goal

    cases = [case for case in boundary_cases(49, 1000) + _edge_cases() if not math.isnan(case[2])]
    for ulps in (4, -4):
        monkeypatch.setattr(goal, "math", _Shifted(ulps))
        for case in cases:
            want = exact_at_goal(*case)
            verdict = goal.goal_verdict(*case)
            if verdict != UNDECIDED:
                assert (verdict == INSIDE) == want, (case, ulps, verdict)
            assert goal.at_goal(*case) == want, (case, ulps)
