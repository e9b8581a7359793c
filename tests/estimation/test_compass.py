"""Compass heading to yaw: the paper's table, properties, calibration and unwrapping."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.estimation import CompassCalibration, compass_to_yaw
from navkit.geometry import angle_diff

# (raw reading, initial heading, expected yaw in degrees) from the paper's rule:
# θr = (θ − θ0 + 360) mod 360; yaw = −θr if θr < 180 else 360 − θr.
TABLE = [
    (0.0, 0.0, 0.0),
    (90.0, 0.0, -90.0),
    (180.0, 0.0, 180.0),
    (270.0, 0.0, 90.0),
    (359.0, 0.0, 1.0),
    (0.0, 90.0, 90.0),
    (90.0, 90.0, 0.0),
    (180.0, 90.0, -90.0),
    (270.0, 90.0, 180.0),
    (359.0, 90.0, 91.0),
    (0.0, 300.0, -60.0),
    (90.0, 300.0, -150.0),
    (180.0, 300.0, 120.0),
    (270.0, 300.0, 30.0),
    (359.0, 300.0, -59.0),
    (10.0, 200.0, -170.0),
    (20.0, 200.0, 180.0),
]


@pytest.mark.parametrize(("raw", "initial", "expected_deg"), TABLE)
def test_table(raw: float, initial: float, expected_deg: float) -> None:
    yaw = compass_to_yaw(raw, initial_deg=initial)
    assert isinstance(yaw, float)
    assert yaw == pytest.approx(math.radians(expected_deg), abs=1e-12)


def test_array_matches_scalars() -> None:
    raws = np.array([row[0] for row in TABLE])
    initials = {row[1] for row in TABLE}
    for initial in initials:
        out = compass_to_yaw(raws, initial_deg=initial)
        assert isinstance(out, np.ndarray)
        assert out.shape == raws.shape
        np.testing.assert_array_equal(
            out, [compass_to_yaw(float(r), initial_deg=initial) for r in raws]
        )


def test_input_not_modified_and_2d_shape_kept() -> None:
    raws = np.array([[0.0, 90.0], [180.0, 270.0]])
    before = raws.copy()
    out = compass_to_yaw(raws)
    np.testing.assert_array_equal(raws, before)
    assert isinstance(out, np.ndarray) and out.shape == (2, 2)


@settings(max_examples=50, deadline=None)
@given(
    raw=st.floats(-720.0, 720.0, allow_nan=False),
    initial=st.floats(0.0, 360.0, allow_nan=False),
    turn=st.floats(0.01, 179.0),
)
def test_range_and_clockwise_is_negative(raw: float, initial: float, turn: float) -> None:
    yaw = compass_to_yaw(raw, initial_deg=initial)
    assert -math.pi < yaw <= math.pi
    # Turning clockwise increases the compass reading and must decrease the yaw.
    after = compass_to_yaw(raw + turn, initial_deg=initial)
    change = angle_diff(after, yaw)
    assert change < 0.0
    assert change == pytest.approx(-math.radians(turn), abs=1e-9)


test_range_and_clockwise_is_negative_thoroughly = slow_twin(
    test_range_and_clockwise_is_negative, max_examples=300
)


def test_unwrap_is_continuous() -> None:
    # A robot spinning clockwise through two full turns in 10° steps.
    raws = np.mod(np.arange(0.0, 720.0, 10.0), 360.0)
    yaw = compass_to_yaw(raws, unwrap=True)
    assert isinstance(yaw, np.ndarray)
    np.testing.assert_allclose(yaw, -np.radians(np.arange(0.0, 720.0, 10.0)), atol=1e-12)
    with pytest.raises(ValueError, match="1-D"):
        compass_to_yaw(np.zeros((2, 2)), unwrap=True)


def test_calibration_latches_first_reading() -> None:
    cal = CompassCalibration()
    assert cal.initial_deg is None
    assert cal(250.0) == 0.0
    assert cal.initial_deg == 250.0
    assert cal(340.0) == pytest.approx(-math.pi / 2)
    out = cal(np.array([160.0, 250.0]))
    np.testing.assert_allclose(out, [math.pi / 2, 0.0])
    cal.reset()
    assert cal.initial_deg is None
    assert cal(np.array([10.0, 20.0]))[0] == 0.0
    assert cal.initial_deg == 10.0


def test_calibration_unwrap_across_calls() -> None:
    cal = CompassCalibration(unwrap=True)
    pieces = [np.arange(0.0, 200.0, 20.0), np.arange(200.0, 360.0, 20.0), np.array([0.0, 20.0])]
    yaw = np.concatenate([np.atleast_1d(cal(p)) for p in pieces])
    np.testing.assert_allclose(yaw, -np.radians(np.arange(0.0, 400.0, 20.0)), atol=1e-12)
    assert cal(40.0) == pytest.approx(-math.radians(400.0))


@pytest.mark.parametrize("bad", [math.nan, math.inf, [0.0, math.nan]])
def test_non_finite_readings_raise(bad: object) -> None:
    with pytest.raises(ValueError, match="raw_deg"):
        compass_to_yaw(bad)  # type: ignore[call-overload]
    with pytest.raises(ValueError, match="raw_deg"):
        CompassCalibration()(bad)  # type: ignore[call-overload]


def test_bad_initial_and_types_raise() -> None:
    with pytest.raises(ValueError, match="initial_deg"):
        compass_to_yaw(10.0, initial_deg=math.nan)
    with pytest.raises(TypeError, match="raw_deg"):
        compass_to_yaw("north")


def test_options_are_keyword_only() -> None:
    with pytest.raises(TypeError, match="positional"):
        compass_to_yaw(10.0, 20.0)  # type: ignore[call-overload]
    with pytest.raises(TypeError, match="positional"):
        CompassCalibration(True)  # type: ignore[call-arg]
    assert compass_to_yaw(10.0, initial_deg=20.0) == pytest.approx(math.radians(10.0))


def exact_yaw(raw: float, initial: float) -> float:
    """The paper's rule in exact rational arithmetic, then rounded once to radians."""
    rel = (Fraction(raw) - Fraction(initial)) % 360
    return math.radians(float(-rel if rel < 180 else 360 - rel))


@settings(max_examples=50, deadline=None)
@given(
    raw=st.floats(-1e300, 1e300, allow_nan=False),
    initial=st.floats(-1e300, 1e300, allow_nan=False),
)
def test_large_readings_are_taken_modulo_360_exactly(raw: float, initial: float) -> None:
    # raw - initial used to round away the smaller of the two once the other was large.
    yaw = compass_to_yaw(raw, initial_deg=initial)
    assert -math.pi < yaw <= math.pi
    assert angle_diff(yaw, exact_yaw(raw, initial)) == pytest.approx(0.0, abs=1e-12)


test_large_readings_are_taken_modulo_360_exactly_thoroughly = slow_twin(
    test_large_readings_are_taken_modulo_360_exactly, max_examples=300
)


@pytest.mark.parametrize(
    ("raw", "initial", "expected_deg"),
    [(1e20, 10.0, 90.0), (10.0, 1e20, -90.0), (-1e17, 45.0, -35.0), (1e300, 1.0, 1.0)],
)
def test_large_readings_known(raw: float, initial: float, expected_deg: float) -> None:
    assert compass_to_yaw(raw, initial_deg=initial) == pytest.approx(math.radians(expected_deg))
    cal = CompassCalibration()
    cal(initial)
    assert np.asarray(cal(np.array([raw])))[0] == pytest.approx(math.radians(expected_deg))


def test_calibration_unwrap_refuses_2d_readings_without_latching() -> None:
    # It used to unwrap a 2-D array in C order and return it 2-D; compass_to_yaw refuses it.
    cal = CompassCalibration(unwrap=True)
    with pytest.raises(ValueError, match=r"raw_deg.*\(2, 2\)"):
        cal(np.array([[0.0, 90.0], [180.0, 270.0]]))
    with pytest.raises(ValueError, match="raw_deg"):
        cal(np.empty((1, 0)))
    assert cal(30.0) == 0.0  # 30° is the first reading latched, not the 0° of the 2-D array
    assert cal.initial_deg == 30.0
    out = cal(np.array([120.0, 210.0]))
    assert isinstance(out, np.ndarray) and out.shape == (2,)
    np.testing.assert_allclose(out, [-math.pi / 2, -math.pi])
    # Without unwrapping a 2-D array keeps its shape.
    plain = CompassCalibration()
    assert np.shape(plain(np.zeros((2, 3)))) == (2, 3)


def test_reading_at_the_initial_heading_is_positive_zero() -> None:
    """Yaw 0 is +0.0, not -0.0 (as the examples print it), for scalars, arrays and calibrations."""
    assert math.copysign(1.0, compass_to_yaw(45.0, initial_deg=45.0)) == 1.0
    assert math.copysign(1.0, compass_to_yaw(1e300)) == 1.0  # 1e300 is 0 modulo 360
    assert not np.any(np.signbit(compass_to_yaw([0.0, 360.0, 720.0])))
    assert math.copysign(1.0, CompassCalibration()(45.0)) == 1.0
    assert not np.any(np.signbit(CompassCalibration(unwrap=True)([10.0, 10.0])))
    assert str(compass_to_yaw(10.0, initial_deg=10.0)) == "0.0"


def test_a_half_turn_step_keeps_its_sign_in_both_unwrappers() -> None:
    """Readings 180° apart: a step of exactly ±π is kept, as numpy.unwrap keeps it.

    CompassCalibration used to turn the step back (-π) into +π: [0, π, 2π].
    """
    want = [0.0, math.pi, 0.0]
    np.testing.assert_array_equal(compass_to_yaw([0.0, 180.0, 0.0], unwrap=True), want)
    np.testing.assert_array_equal(CompassCalibration(unwrap=True)([0.0, 180.0, 0.0]), want)
    cal = CompassCalibration(unwrap=True)
    assert [cal(d) for d in (0.0, 180.0, 0.0, 180.0)] == [*want, math.pi]
    # 270° then 90° from a start at 0°: yaw π/2, then a step of exactly -π.
    cal = CompassCalibration(unwrap=True)
    assert [cal(d) for d in (0.0, 270.0, 90.0)] == [0.0, math.pi / 2, -math.pi / 2]


readings = st.sampled_from([0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0]) | st.floats(
    -720.0, 720.0
)


@settings(max_examples=50, deadline=None)
@given(
    log=st.lists(readings, min_size=1, max_size=40),
    cuts=st.lists(st.integers(0, 40), max_size=5),
)
def test_calibration_in_pieces_equals_compass_to_yaw_and_numpy_unwrap(
    log: list[float], cuts: list[int]
) -> None:
    raws = np.array(log)
    whole = compass_to_yaw(raws, initial_deg=log[0], unwrap=True)
    assert isinstance(whole, np.ndarray)
    wrapped = compass_to_yaw(raws, initial_deg=log[0])
    # numpy.unwrap's rule, whole turns counted as integers (review 53): its running sum
    # of rounded corrections is an ulp or two off from the first turn on.
    turns = np.rint((whole - wrapped) / (2 * np.pi))
    np.testing.assert_array_equal(whole, wrapped + turns * (2 * np.pi))
    np.testing.assert_allclose(whole, np.unwrap(wrapped), rtol=0, atol=1e-12)
    cal = CompassCalibration(unwrap=True)
    pieces = np.split(raws, sorted(c for c in cuts if c < len(log)))
    streamed = np.concatenate([np.atleast_1d(cal(p)) for p in pieces])
    np.testing.assert_array_equal(streamed, whole)
    # The same one reading at a time (floats, not arrays).
    cal = CompassCalibration(unwrap=True)
    np.testing.assert_array_equal([cal(float(r)) for r in log], whole)


test_calibration_in_pieces_equals_compass_to_yaw_and_numpy_unwrap_thoroughly = slow_twin(
    test_calibration_in_pieces_equals_compass_to_yaw_and_numpy_unwrap, max_examples=300
)
