"""DiffDrive: the batch twists' vy column, one given radius, and the overflow retries' operands.

Review 39 (mutation testing, MUTANT10) of ``navkit.kinematics._diff``:

* ``forward_batch`` fills its result, made by ``np.empty``, column by column; its
  ``out[:, 1] = 0.0`` deleted (or written to column 2) passed every test, because a
  fresh allocation happened to be zeros: after memory that held other values was
  freed, the vy column came back holding them.
* ``DiffDrive(track=..., left_radius=...)`` with no right radius must say to give
  both (``left_radius is None or right_radius is None`` read as ``and``).
* The retry of ``inverse``/``inverse_batch``/``forward``/``forward_batch`` when a
  partial result overflows: checked against exact rational arithmetic
  (``fractions.Fraction``) where one wheel's or the twist's partial overflows and
  vx differs from omega.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from navkit.kinematics import DiffDrive


def test_the_batch_twists_lateral_column_is_zero_whatever_the_memory_held() -> None:
    drives = [
        DiffDrive(track=0.3, wheel_radius=0.05),
        DiffDrive(track=0.3, left_radius=0.05, right_radius=0.0505),
        DiffDrive(track=0.3, left_radius=0.05, right_radius=0.08),
    ]
    rng = np.random.default_rng(39)
    for drive in drives:
        for n in (1, 3, 64, 1000, 20_000):
            w = rng.normal(size=(n, 2))
            junk = np.full((n, 3), 7.0)  # freed just before: np.empty may hand it back
            del junk
            out = drive.forward_batch(w)
            assert out.shape == (n, 3)
            assert not np.signbit(out[:, 1]).any() and (out[:, 1] == 0.0).all()
            single = np.array([drive.forward(row).as_array() for row in w[:20]])
            assert out[:20].tobytes() == single.tobytes()


@pytest.mark.parametrize("given", [{"left_radius": 0.05}, {"right_radius": 0.05}])
def test_one_radius_alone_is_refused_asking_for_both(given: dict[str, float]) -> None:
    with pytest.raises(ValueError, match=r"^give wheel_radius, or both left_radius and"):
        DiffDrive(track=0.3, **given)


_MAX = Fraction(np.finfo(np.float64).max)


def _floats(values: list[Fraction]) -> list[float] | None:
    """The values rounded to float64, or None if one lies beyond its range."""
    return None if any(abs(v) > _MAX for v in values) else [float(v) for v in values]


def _exact_wheels(drive: DiffDrive, vx: float, omega: float) -> list[float] | None:
    half = Fraction(omega) * Fraction(drive.track) / 2
    return _floats(
        [
            (Fraction(vx) - half) / Fraction(drive.left_radius),
            (Fraction(vx) + half) / Fraction(drive.right_radius),
        ]
    )


def _exact_twist(drive: DiffDrive, left: float, right: float) -> list[float] | None:
    wl = Fraction(left) * Fraction(drive.left_radius)
    wr = Fraction(right) * Fraction(drive.right_radius)
    return _floats([(wr + wl) / 2, Fraction(0), (wr - wl) / Fraction(drive.track)])


@pytest.mark.parametrize(
    "drive",
    [
        DiffDrive(track=2.0, wheel_radius=1e6),
        DiffDrive(track=2.0, left_radius=1e6, right_radius=5e5),
        DiffDrive(track=4.0, left_radius=3e5, right_radius=1e6),
    ],
)
def test_wheel_speeds_whose_partial_sums_overflow_are_exact(drive: DiffDrive) -> None:
    twists = [
        [1.5e308, 0.0, 1e308],  # vx + ω D/2 overflows
        [-1.5e308, 0.0, 1e308],  # vx - ω D/2 overflows
        [1.2e308, 0.0, -0.7e308],
        [0.25, 0.0, 1.5e308],  # ω D/2 alone overflows (D = 4)
    ]
    rows = []
    for tw in twists:
        expected = _exact_wheels(drive, tw[0], tw[2])
        if expected is None:
            continue
        got = drive.inverse(tw)
        np.testing.assert_allclose(got, expected, rtol=4e-16, atol=0.0)
        rows.append((tw, got))
    assert len(rows) >= 3
    batch = drive.inverse_batch([tw for tw, _ in rows])
    assert batch.tobytes() == np.array([g for _, g in rows]).tobytes()


@pytest.mark.parametrize(
    "drive",
    [
        DiffDrive(track=2.0, wheel_radius=1.0),
        DiffDrive(track=3.0, left_radius=1.0, right_radius=0.5),
        DiffDrive(track=1e6, left_radius=1.0, right_radius=1.0 + 2.0**-10),
    ],
)
def test_twists_whose_partial_sums_overflow_are_exact(drive: DiffDrive) -> None:
    speeds = [[1.5e308, 1.2e308], [-1.5e308, -1.0e308], [1e308, -1.7e308], [1.7e308, 3.0]]
    rows = []
    for left, right in speeds:
        expected = _exact_twist(drive, left, right)
        if expected is None:
            continue
        got = drive.forward([left, right]).as_array()
        np.testing.assert_allclose(got, expected, rtol=4e-16, atol=0.0)
        rows.append(([left, right], got))
    assert len(rows) >= 2
    batch = drive.forward_batch([s for s, _ in rows])
    assert batch.tobytes() == np.array([g for _, g in rows]).tobytes()


def test_tiny_twists_keep_full_precision() -> None:
    # Normal floats far below 1: the overflow retry (operands scaled by 2**-48) must
    # not be taken, its scaled operands would be subnormal and lose digits.
    drive = DiffDrive(track=0.3, left_radius=0.05, right_radius=0.08)
    twists = [[3e-300, 0.0, 1e-300], [-1.7e-300, 0.0, 2.9e-300], [1e-307, 0.0, -1e-307]]
    for tw in twists:
        expected = _exact_wheels(drive, tw[0], tw[2])
        np.testing.assert_allclose(drive.inverse(tw), expected, rtol=4e-16, atol=0.0)
    speeds = [[3e-300, 1e-300], [-1.7e-300, 2.9e-300], [1e-307, -1e-307]]
    for left, right in speeds:
        expected = _exact_twist(drive, left, right)
        np.testing.assert_allclose(drive.forward([left, right]).as_array(), expected, rtol=4e-16)
