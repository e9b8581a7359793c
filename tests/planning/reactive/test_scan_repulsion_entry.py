"""``repulsive_force_from_scan``'s compiled-entry path and its beam-table memo."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping import LaserScan
from navkit.planning import KhatibRepulsion, repulsive_force_from_scan
from navkit.planning.reactive._limits import MIN_DISTANCE
from navkit.planning.reactive._scan_repulsion import _beam_table
from navkit.planning.reactive._scan_repulsion_kernels import khatib_beam_force


class _SubScan(LaserScan):
    """A LaserScan subclass: takes the dispatcher path, not the compiled entry."""

    __slots__ = ()


def _scan(cls: Any, ranges: np.ndarray, angle_min: float, inc: float) -> LaserScan:
    out: LaserScan = cls(ranges, angle_min=angle_min, angle_increment=inc, range_min=0.05,
                         range_max=4.0)
    return out


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(1, 400),
    angle_min=st.floats(-3.0, 0.0),
    k=st.floats(0.1, 10.0),
    d0=st.floats(0.1, 3.0),
)
def test_entry_path_equals_kernel_and_subclass_path(
    seed: int, n: int, angle_min: float, k: float, d0: float
) -> None:
    ranges = np.random.default_rng(seed).uniform(0.0, 5.0, n)
    ranges[::7] = math.nan
    inc = 3.0 / n
    scan = _scan(LaserScan, ranges, angle_min, inc)
    sub = _scan(_SubScan, ranges, angle_min, inc)
    got = repulsive_force_from_scan(scan, k_rep=k, influence_radius=d0)
    cos_t, sin_t = _beam_table(scan)
    want = khatib_beam_force(
        scan.ranges, cos_t, sin_t, scan.range_min, scan.range_max, k, d0, MIN_DISTANCE
    )
    assert got.dtype == np.float64 and got.shape == (2,)
    assert got.tolist() == list(want)
    assert np.array_equal(repulsive_force_from_scan(sub, k_rep=k, influence_radius=d0), got)


def test_alternating_geometries_use_their_own_tables() -> None:
    ranges = np.linspace(0.2, 0.9, 90)
    scans = [
        _scan(LaserScan, ranges, -1.0, 0.02),
        _scan(LaserScan, ranges, -1.0, 0.021),
        _scan(LaserScan, ranges, -1.1, 0.02),
        _scan(LaserScan, ranges[:89], -1.0, 0.02),
    ]
    want = [
        KhatibRepulsion(s.to_points(), k_rep=1.0, influence_radius=1.0).force([0.0, 0.0])[0]
        for s in scans
    ]
    for _ in range(3):
        for scan, w in zip(scans, want, strict=True):
            got = repulsive_force_from_scan(scan)
            np.testing.assert_allclose(got, w, rtol=1e-12)


def test_results_are_new_arrays_and_scan_is_untouched() -> None:
    scan = _scan(LaserScan, np.array([0.5, 0.7, math.inf]), 0.0, 0.5)
    before = scan.ranges.copy()
    a = repulsive_force_from_scan(scan)
    b = repulsive_force_from_scan(scan)
    assert a is not b and not np.shares_memory(a, b) and a.flags.writeable
    assert np.array_equal(scan.ranges, before)


def test_parameters_are_checked_on_every_path() -> None:
    scan = _scan(LaserScan, np.array([0.5]), 0.0, 0.5)
    sub = _scan(_SubScan, np.array([0.5]), 0.0, 0.5)
    for s in (scan, sub):
        with pytest.raises(ValueError, match="k_rep"):
            repulsive_force_from_scan(s, k_rep=0.0)
        with pytest.raises(TypeError, match="influence_radius"):
            repulsive_force_from_scan(s, influence_radius=True)
        # ints and numpy floats are accepted, as floats
        assert np.array_equal(
            repulsive_force_from_scan(s, k_rep=1, influence_radius=np.float64(1.0)),
            repulsive_force_from_scan(s, k_rep=1.0, influence_radius=1.0),
        )
    with pytest.raises(TypeError, match="scan"):
        repulsive_force_from_scan(np.array([0.5]), k_rep=1.0)  # type: ignore[arg-type]
