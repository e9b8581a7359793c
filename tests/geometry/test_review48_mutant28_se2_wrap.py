"""The compiled kernels wrap a heading bit for bit as ``wrap_angle`` does, also below -π.

Review 48 (mutation testing, MUTANT28). ``_shared.se2.wrap_scalar`` (behind
``integrate``, ``rollout`` and every kernel that turns a pose) reduces
``|a| mod 2π`` with the sign of ``a``: ``fmod``, exact, as
``_shared.angles.wrap_float``. Its reduction read as Python's ``a % 2π`` (for a
negative ``a``: ``fmod`` plus ``2π``, rounded, then folded again) passed every
test. For every heading beyond -π that reduction is exact too (``fmod``'s
remainder is a multiple of the spacing of floats near 2π, so adding 2π and
folding back rounds nothing); only the sign of a zero differs: a turn ending
exactly at -2π·k gave +0.0 where ``wrap_angle`` (and ``Pose2D``) give -0.0.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.geometry import Pose2D, Twist2D, integrate, rollout, wrap_angle

RNG = np.random.default_rng(48028)
# Turns (omega * dt, rad) of either sign from a few to 1e9 half-turns, and headings.
TURNS = np.concatenate(
    [
        -np.exp(RNG.uniform(math.log(4.0), math.log(3e9), 60)),
        np.exp(RNG.uniform(math.log(4.0), math.log(3e9), 20)),
        [-1e6, -123456.789, -4.0, -7.0, -1e9 - 0.5],
    ]
)
# Turns that end exactly at a multiple of -2π (the float 2 * math.pi).
WHOLE_TURNS = [-2 * math.pi, -4 * math.pi, -8 * math.pi, -64 * math.pi, 2 * math.pi]
HEADINGS = RNG.uniform(-math.pi, math.pi, TURNS.size)


def _bits(x: float) -> str:
    return float(x).hex()


@pytest.mark.parametrize("dt", [1.0, 0.5])
def test_integrate_wraps_the_heading_as_wrap_angle(dt: float) -> None:
    for turn, heading in zip(TURNS.tolist(), HEADINGS.tolist(), strict=True):
        omega = turn / dt
        got = integrate(Pose2D(0.0, 0.0, heading), Twist2D(0.0, 0.0, omega), dt).theta
        want = wrap_angle(heading + omega * dt)
        assert _bits(got) == _bits(want), (heading, omega, dt)


@pytest.mark.parametrize("turn", WHOLE_TURNS)
def test_whole_turns_end_at_the_signed_zero_of_wrap_angle(turn: float) -> None:
    want = wrap_angle(turn)
    assert want == 0.0
    got = integrate(Pose2D(0.0, 0.0, 0.0), Twist2D(0.0, 0.0, turn), 1.0).theta
    assert _bits(got) == _bits(want) == _bits(Pose2D(0.0, 0.0, turn).theta)
    rows = rollout(Pose2D(0.0, 0.0, 0.0), [[0.0, 0.0, turn]], 1.0)
    assert _bits(rows[1, 2]) == _bits(want)


def test_rollout_rows_wrap_the_heading_as_wrap_angle() -> None:
    twists = np.zeros((TURNS.size, 3))
    twists[:, 2] = TURNS
    rows = rollout(Pose2D(0.0, 0.0, 0.0), twists, 1.0)
    heading = 0.0
    for i, turn in enumerate(TURNS.tolist()):
        heading = wrap_angle(heading + turn)
        assert _bits(rows[i + 1, 2]) == _bits(heading), i
        assert -math.pi < rows[i + 1, 2] <= math.pi
