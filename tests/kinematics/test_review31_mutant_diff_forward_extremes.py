"""``DiffDrive.forward`` at the ends of float64 (review 31, mutants).

``forward`` computes the twist directly and, where an intermediate overflowed,
again on speeds scaled by 2⁻⁴⁸. Two mutants of its finiteness tests passed the
suite: ``vx + vx == 0`` in the test after the rescaled pass refused a finite
twist of huge equal speeds (the sum ``right + left`` overflows, the twist does
not), and ``omega + omega == 0`` in the first test sent every turning twist
through the rescaled pass, where speeds near 1e-300 become subnormal and lose
digits (a relative error of 1.5e-9). In ``inverse``, ``or`` for ``and`` in the
first finiteness test returned an infinite wheel speed where only one wheel's
partial sum ``vx ± ωD/2`` overflowed (large wheels), and a test that never
held sent every twist through the rescaled pass (tiny twists lost digits).
Oracle: the twist in exact rational
arithmetic on the float inputs, rounded once. Checked: each test fails on its
mutant of ``_diff.py`` and passes on HEAD.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from navkit.kinematics import DiffDrive


def _exact(track: float, radius: float, left: float, right: float) -> tuple[float, float]:
    r = Fraction(radius)
    vx = (Fraction(left) + Fraction(right)) * r / 2
    omega = (Fraction(right) - Fraction(left)) * r / Fraction(track)
    return float(vx), float(omega)


@pytest.mark.parametrize("speed", [1.5e308, -1.7e308, 9e307])
def test_huge_equal_speeds_give_their_finite_twist(speed: float) -> None:
    drive = DiffDrive(track=0.3, wheel_radius=0.5)
    twist = drive.forward([speed, speed])
    vx, omega = _exact(0.3, 0.5, speed, speed)
    assert (twist.vx, twist.vy, twist.omega) == (vx, 0.0, omega)


@pytest.mark.parametrize(("left", "right"), [(3e-300, 5e-300), (-2e-305, 7e-306), (1e-290, 0.0)])
def test_tiny_turning_speeds_keep_their_digits(left: float, right: float) -> None:
    drive = DiffDrive(track=0.3, wheel_radius=0.05)
    vx, omega = _exact(0.3, 0.05, left, right)
    twist = drive.forward([left, right])
    assert twist.vx == pytest.approx(vx, rel=1e-14, abs=0.0)
    assert twist.omega == pytest.approx(omega, rel=1e-14, abs=0.0)


def _exact_wheels(track: float, radius: float, vx: float, omega: float) -> list[float]:
    half = Fraction(omega) * Fraction(track) / 2
    r = Fraction(radius)
    return [float((Fraction(vx) - half) / r), float((Fraction(vx) + half) / r)]


@pytest.mark.parametrize("omega", [-1e308, 1e308])
def test_one_wheels_overflowing_partial_sum_gives_its_finite_speed(omega: float) -> None:
    drive = DiffDrive(track=0.5, wheel_radius=10.0)
    wheels = drive.inverse([1.7e308, 0.0, omega])  # 1.7e308 + 2.5e307 overflows
    assert wheels.tolist() == _exact_wheels(0.5, 10.0, 1.7e308, omega)


@pytest.mark.parametrize(("vx", "omega"), [(3e-300, 5e-300), (-2e-305, 7e-306)])
def test_a_tiny_twist_gives_wheel_speeds_with_their_digits(vx: float, omega: float) -> None:
    drive = DiffDrive(track=0.5, wheel_radius=0.05)
    wheels = drive.inverse([vx, 0.0, omega])
    np.testing.assert_allclose(wheels, _exact_wheels(0.5, 0.05, vx, omega), rtol=1e-14, atol=0.0)
