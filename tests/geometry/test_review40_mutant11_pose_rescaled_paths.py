"""Pose2D's rescaled retries give the exact result's rounding in both coordinates.

Review 40 (mutation testing, MUTANT11). ``compose``, ``relative_to`` and
``transform_points`` retry at an eighth of the size where a partial sum overflows
but the result does not. In ``relative_to`` the retry's ``self.y * _SHRINK`` read
as ``self.y / _SHRINK``, and its ``dx`` left unscaled (the line deleted), passed
every test: the hypothesis tests near the float limit (40 examples) did not
happen to draw a case that reaches the retry with a finite result and a
non-zero ``y``. Here the cases are searched for (seeded): both coordinates
non-zero, a partial sum of the plain formula overflowing, the exact result
within the float range. Also: the plain path (not the retry) for subnormal
coordinates, where a retry at an eighth of the size would lose their last bits
(the overflow check's ``y - y == 0.0`` read as ``!=``, sending every call to the
retry, passed every test too). Oracle: exact rational arithmetic with the
pose's float ``cos``/``sin``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from fractions import Fraction

import numpy as np
import pytest

from navkit.geometry import Pose2D

TOP = Fraction(np.finfo(np.float64).max)
EPS = Fraction(2) ** -52


def _plain_overflows(parts: list[tuple[float, ...]]) -> bool:
    """Whether a left-to-right float sum of each term list overflows on the way."""
    for terms in parts:
        total = 0.0
        for t in terms:
            total += t
            if not math.isfinite(total):
                return True
    return False


def _search(
    build: Callable[
        [np.random.Generator], tuple[tuple[Fraction, Fraction], list[tuple[float, ...]]]
    ],
    seed: int,
) -> list[int]:
    """Seeds of cases whose plain formula overflows but whose exact result is finite."""
    found = []
    for k in range(4000):
        rng = np.random.default_rng([seed, k])
        exact, parts = build(rng)
        if (
            max(abs(v) for v in exact) < TOP * Fraction(9, 10)
            and min(abs(v) for v in exact) > 1e300
            and _plain_overflows(parts)
        ):
            found.append(k)
        if len(found) == 12:
            break
    return found


def _huge(rng: np.random.Generator) -> float:
    return float(rng.uniform(-1.0, 1.0)) * 1.7e308


def _check(got: tuple[float, float], exact: tuple[Fraction, Fraction], scale: Fraction) -> None:
    for value, want in zip(got, exact, strict=True):
        assert math.isfinite(value)
        assert abs(Fraction(value) - want) <= 8 * EPS * scale


def _relative_case(
    rng: np.random.Generator,
) -> tuple[tuple[Fraction, Fraction], list[tuple[float, ...]]]:
    x, y, fx, fy = (_huge(rng) for _ in range(4))
    theta = float(rng.uniform(-math.pi, math.pi))
    c, s = math.cos(theta), math.sin(theta)
    dx, dy = Fraction(x) - Fraction(fx), Fraction(y) - Fraction(fy)
    exact = (Fraction(c) * dx + Fraction(s) * dy, Fraction(c) * dy - Fraction(s) * dx)
    parts = [(x, -fx), (y, -fy)]
    return exact, parts


def _relative_args(seed: int) -> tuple[float, ...]:
    rng = np.random.default_rng([1, seed])
    x, y, fx, fy = (_huge(rng) for _ in range(4))
    return x, y, fx, fy, float(rng.uniform(-math.pi, math.pi))


def test_relative_to_retry_in_both_coordinates() -> None:
    seeds = _search(_relative_case, 1)
    assert len(seeds) == 12
    for k in seeds:
        x, y, fx, fy, theta = _relative_args(k)
        exact, _ = _relative_case(np.random.default_rng([1, k]))
        out = Pose2D(x, y, 0.5).relative_to(Pose2D(fx, fy, theta))
        scale = abs(Fraction(x) - Fraction(fx)) + abs(Fraction(y) - Fraction(fy))
        _check((out.x, out.y), exact, scale)


def _compose_case(
    rng: np.random.Generator,
) -> tuple[tuple[Fraction, Fraction], list[tuple[float, ...]]]:
    x, y, ox, oy = (_huge(rng) for _ in range(4))
    theta = float(rng.uniform(-math.pi, math.pi))
    c, s = math.cos(theta), math.sin(theta)
    exact = (
        Fraction(x) + Fraction(c) * Fraction(ox) - Fraction(s) * Fraction(oy),
        Fraction(y) + Fraction(s) * Fraction(ox) + Fraction(c) * Fraction(oy),
    )
    parts = [(x, c * ox, -s * oy), (y, s * ox, c * oy)]
    return exact, parts


def test_compose_and_transform_points_retry_in_both_coordinates() -> None:
    seeds = _search(_compose_case, 2)
    assert len(seeds) == 12
    for k in seeds:
        rng = np.random.default_rng([2, k])
        x, y, ox, oy = (_huge(rng) for _ in range(4))
        theta = float(rng.uniform(-math.pi, math.pi))
        exact, _ = _compose_case(np.random.default_rng([2, k]))
        scale = abs(Fraction(x)) + abs(Fraction(y)) + abs(Fraction(ox)) + abs(Fraction(oy))
        pose = Pose2D(x, y, theta)
        out = pose.compose([ox, oy, 0.25])
        _check((out.x, out.y), exact, scale)
        point = pose.transform_points([[ox, oy], [0.0, 0.0]])
        _check((float(point[0, 0]), float(point[0, 1])), exact, scale)
        assert point[1].tolist() == [x, y]  # the other point: a call of its own


TINY = [5e-324, -1.5e-323, 2.5e-322, -7.4e-320, 2.2250738585072014e-308]


@pytest.mark.parametrize("a", TINY)
@pytest.mark.parametrize("b", TINY)
def test_subnormal_coordinates_are_exact_without_a_turn(a: float, b: float) -> None:
    # With heading 0 every result is a sum or difference of the inputs: exact in
    # floats for these (subnormal sums are exact). A retry at an eighth of the
    # size would round their last bits away.
    frame = Pose2D(b, a, 0.0)
    pose = Pose2D(a, b, 0.0)
    rel = pose.relative_to(frame)
    assert (Fraction(rel.x), Fraction(rel.y)) == (
        Fraction(a) - Fraction(b),
        Fraction(b) - Fraction(a),
    )
    out = frame.compose(pose)
    assert (Fraction(out.x), Fraction(out.y)) == (
        Fraction(b) + Fraction(a),
        Fraction(a) + Fraction(b),
    )
    pts = frame.transform_points([[a, b]])
    assert [Fraction(v) for v in pts[0]] == [Fraction(b) + Fraction(a), Fraction(a) + Fraction(b)]
