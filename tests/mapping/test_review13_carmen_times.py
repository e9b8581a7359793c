"""CARMEN log times: as logged, in file order, each the float64 nearest its text.

A log's ``timestamp`` field is read with ``float`` (correctly rounded: within half a
spacing, 1.2e-7 s at epoch stamps of 1.7e9 s) and kept in file order, neither sorted
nor checked: Radish's intel log steps back four times (by up to 0.86 s), csail
prints six significant digits and gives runs of equal times.
"""

from __future__ import annotations

import gzip
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.mapping.io import read_carmen

LOGS = "carmen-logs"


def _flaser_times(path: Path) -> list[str]:
    """The ``timestamp`` field of every FLASER line, as text (read independently)."""
    out = []
    with gzip.open(path, "rt") as f:
        for line in f:
            tokens = line.split()
            if tokens and tokens[0] == "FLASER":
                out.append(tokens[int(tokens[1]) + 8])
    return out


def test_intel_times_are_the_logged_ones_in_file_order(shared_data: Path) -> None:
    path = shared_data / LOGS / "intel-corrected.log.gz"
    text = _flaser_times(path)
    times = read_carmen(path).times
    assert times.dtype == np.float64 and len(times) == len(text) == 910
    np.testing.assert_array_equal(times, [float(Fraction(t)) for t in text])
    steps = np.diff(times)
    assert int(np.sum(steps < 0.0)) == 4 and steps.min() > -0.87  # not sorted


def test_csail_six_digit_times_stay_equal(shared_data: Path) -> None:
    times = read_carmen(shared_data / LOGS / "csail-corrected.log.gz").times
    steps = np.diff(times)
    assert times[0] > 1e9 and np.all(steps >= 0.0) and int(np.sum(steps == 0.0)) > 400 * 0.9


@settings(max_examples=30, deadline=None)
@given(
    sec=st.integers(1_000_000_000, 2_000_000_000),
    nsec=st.lists(st.integers(0, 999_999_999), min_size=1, max_size=8),
)
def test_epoch_timestamps_are_correctly_rounded_and_not_reordered(
    tmp_path_factory: pytest.TempPathFactory, sec: int, nsec: list[int]
) -> None:
    stamps = [f"{sec}.{n:09d}" for n in nsec]  # any order, repeats allowed
    lines = "".join(f"FLASER 3 1.0 2.0 5.0 0 0 0 0 0 0 {s} host {s}\n" for s in stamps)
    folder = tmp_path_factory.mktemp("carmen")
    path = folder / "log.txt"
    path.write_text(lines)
    times = read_carmen(path).times
    np.testing.assert_array_equal(times, [float(Fraction(s)) for s in stamps])
    assert np.all(np.abs(times - sec - np.array(nsec) * 1e-9) <= 2.0**-23)


test_epoch_timestamps_are_correctly_rounded_and_not_reordered_thoroughly = slow_twin(
    test_epoch_timestamps_are_correctly_rounded_and_not_reordered, max_examples=200
)
