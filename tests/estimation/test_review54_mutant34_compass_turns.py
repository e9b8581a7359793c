"""Review 54 (MUTANT34): compass turns are counted from every kind of jump.

Review 53 counts the whole turns of an unwrapped compass yaw as integers,
rounding each correction over 2π to the nearest integer. Truncating it instead
passed the tests: their jumps gave corrections of exactly ±2π. Random
headings, whose steps' corrections come out a hair inside ±2π, must unwrap as
``numpy.unwrap`` does (to its rounding: the two differ in the last bits).
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import CompassCalibration, compass_to_yaw


@pytest.mark.parametrize("seed", range(5))
def test_random_headings_unwrap_as_numpy_does(seed: int) -> None:
    rng = np.random.default_rng(5434 + seed)
    raw = rng.uniform(0.0, 360.0, size=2000)
    yaw = compass_to_yaw(raw, initial_deg=float(raw[0]), unwrap=True)
    wrapped = compass_to_yaw(raw, initial_deg=float(raw[0]))
    reference = np.unwrap(wrapped)
    assert np.max(np.abs(yaw - reference)) < 1e-9
    # Every yaw is its wrapped value plus whole turns.
    turns = (yaw - wrapped) / (2.0 * np.pi)
    assert np.max(np.abs(turns - np.rint(turns))) < 1e-12


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.floats(0.0, 360.0, allow_nan=False, exclude_max=True), min_size=2, max_size=40),
    st.integers(1, 5),
)
def test_a_log_in_pieces_unwraps_as_numpy_does(raw: list[float], pieces: int) -> None:
    wrapped = compass_to_yaw(raw, initial_deg=raw[0])
    reference = np.unwrap(wrapped)
    calibration = CompassCalibration(unwrap=True)  # latches raw[0]
    bounds = np.linspace(0, len(raw), pieces + 1).astype(int)
    parts = [calibration(raw[a:b]) for a, b in itertools.pairwise(bounds) if b > a]
    yaw = np.concatenate(parts)
    assert np.max(np.abs(yaw - reference)) < 1e-9


def test_an_empty_piece_keeps_the_turns_counted_so_far() -> None:
    # Clockwise by 170 degrees a reading: a turn every few readings.
    raw = [(170.0 * i) % 360.0 for i in range(40)]
    whole = compass_to_yaw(raw, initial_deg=raw[0], unwrap=True)
    assert abs(whole[-1]) > 4 * 2.0 * np.pi  # the premise: several turns
    calibration = CompassCalibration(unwrap=True)
    first = calibration(raw[:20])
    assert np.shape(calibration(np.array([]))) == (0,)
    assert np.shape(calibration([])) == (0,)
    rest = calibration(raw[20:])
    assert np.array_equal(np.concatenate((first, rest)), whole)
