"""``repulsive_force_from_scan``: the last-table check and the refcount-free kernels (session 23).

The public call compares the last beam table's geometry with the scan's by
``len(scan.ranges)`` (no shape tuple) and ends in the compiled entry of a
kernel built without numba's reference counting. Scans that share
``angle_min`` and ``angle_increment`` but not their beam count must still get
their own table, and every call must equal the kernel on freshly computed
tables, bit for bit.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit._shared.jit import jit_disabled
from navkit.mapping import LaserScan
from navkit.planning import repulsive_force_from_scan
from navkit.planning.reactive._limits import MIN_DISTANCE
from navkit.planning.reactive._scan_repulsion import piecewise_repulsive_force_from_scan
from navkit.planning.reactive._scan_repulsion_kernels import (
    khatib_beam_force,
    khatib_beam_force_into,
    piecewise_beam_force,
)


def _scan(ranges: list[float], angle_min: float, inc: float) -> LaserScan:
    return LaserScan(ranges, angle_min=angle_min, angle_increment=inc,
                     range_min=0.05, range_max=3.5)  # fmt: skip


def _want(scan: LaserScan, k_rep: float, d0: float) -> np.ndarray:
    angles = scan.angles()
    fx, fy = khatib_beam_force(
        scan.ranges, np.cos(angles), np.sin(angles), scan.range_min, scan.range_max,
        k_rep, d0, MIN_DISTANCE,
    )  # fmt: skip
    return np.array([fx, fy])


_RANGE = st.one_of(st.floats(0.0, 4.0), st.sampled_from([math.nan, math.inf, 1e-300]))


@given(
    st.lists(st.lists(_RANGE, min_size=1, max_size=40), min_size=2, max_size=6),
    st.sampled_from([-math.pi, -1.0, 0.0]),
    st.sampled_from([0.1, 2.0 * math.pi / 360.0]),
    st.floats(0.1, 3.0),
)
@settings(max_examples=40, deadline=None)
def test_same_geometry_other_beam_counts(
    scans: list[list[float]], angle_min: float, inc: float, d0: float
) -> None:
    """Scans alike but for their length, in turn: each call uses its own table."""
    built = [_scan(r, angle_min, inc) for r in scans]
    for scan in built + built[::-1]:
        ranges = scan.ranges.copy()
        got = repulsive_force_from_scan(scan, k_rep=0.5, influence_radius=d0)
        assert got.shape == (2,) and got.dtype == np.float64 and got.flags.writeable
        assert got.tobytes() == _want(scan, 0.5, d0).tobytes()
        np.testing.assert_array_equal(scan.ranges, ranges)


def test_fresh_result_every_call() -> None:
    scan = _scan([0.5, 0.7, 2.0], 0.0, 0.3)
    a = repulsive_force_from_scan(scan)
    b = repulsive_force_from_scan(scan)
    assert a is not b and not np.shares_memory(a, b)
    a[:] = 0.0
    assert np.array_equal(b, _want(scan, 1.0, 1.0))


def test_bad_parameters_still_named() -> None:
    scan = _scan([0.5, 0.7], 0.0, 0.3)
    with pytest.raises(TypeError, match="scan"):
        repulsive_force_from_scan([0.5, 0.7])  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="k_rep"):
        repulsive_force_from_scan(scan, k_rep=-1.0)
    with pytest.raises(ValueError, match="influence_radius"):
        repulsive_force_from_scan(scan, influence_radius=0.0)
    with pytest.raises(TypeError, match="influence_radius"):
        repulsive_force_from_scan(scan, influence_radius=True)


def test_piecewise_unchanged_by_refcount_free_kernel() -> None:
    scan = _scan([0.2, 0.5, math.nan, 1.1, 3.0], -1.0, 0.4)
    angles = scan.angles()
    want = piecewise_beam_force(
        scan.ranges, np.cos(angles), np.sin(angles), scan.range_min, scan.range_max,
        2.0, 1.5, 0.3, 1.2,
    )  # fmt: skip
    got = piecewise_repulsive_force_from_scan(
        scan, delta=2.0, beta=1.5, obstacle_radius=0.3, spread=1.2
    )
    assert got.tobytes() == np.array(want).tobytes()


@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: plain functions")
def test_kernels_compiled_without_refcounting() -> None:
    """No MemInfo per array argument per call: the kernels allocate nothing."""
    for kernel in (khatib_beam_force, khatib_beam_force_into, piecewise_beam_force):
        dispatcher: Any = kernel
        options = dispatcher.targetoptions  # loads numba: a dispatcher
        assert options.get("_nrt") is False, kernel
        assert options.get("fastmath") == {"reassoc", "contract"}, kernel
