"""``repulsive_force_from_scan`` with the (2, N) beam-direction table (session 27).

The public call passes one read-only (2, N) table of the beam cosines and sines
to ``khatib_beam_force_into`` instead of two arrays (one array fewer to unbox
per call). The kernel sums with the ``reassoc`` fast-math flag, so LLVM may
order the sum as it likes: these tests check that the table's rows give the
sum of separate, freshly computed cosine and sine arrays bit for bit, over
random scans of every length up to a few SIMD widths and beyond.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping import LaserScan
from navkit.planning import repulsive_force_from_scan
from navkit.planning.reactive._limits import MIN_DISTANCE
from navkit.planning.reactive._scan_repulsion import _beam_directions, _beam_table
from navkit.planning.reactive._scan_repulsion_kernels import (
    khatib_beam_force,
    khatib_beam_force_into,
    khatib_entry,
)


class _SubScan(LaserScan):
    """A LaserScan subclass: the dispatcher path, not the compiled entry."""

    __slots__ = ()


_SPECIAL = [math.nan, math.inf, -math.inf, 0.0, 1e-300, 1e-12, 0.05, 0.12, 3.5]


def _want(scan: LaserScan, k_rep: float, d0: float) -> bytes:
    """The force from separate cosine and sine arrays (the tables before the change)."""
    angles = scan.angles()
    fx, fy = khatib_beam_force(
        scan.ranges, np.cos(angles), np.sin(angles), scan.range_min, scan.range_max,
        k_rep, d0, MIN_DISTANCE,
    )  # fmt: skip
    return np.array([fx, fy]).tobytes()


@settings(max_examples=150, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(1, 1100),
    special=st.floats(0.0, 0.5),
    angle_min=st.floats(-math.pi, 0.0),
    k_rep=st.floats(1e-3, 1e3),
    d0=st.floats(0.05, 5.0),
)
def test_table_sum_equals_separate_arrays_bit_for_bit(
    seed: int, n: int, special: float, angle_min: float, k_rep: float, d0: float
) -> None:
    rng = np.random.default_rng(seed)
    ranges = rng.uniform(0.0, 4.0, n)
    picks = rng.random(n) < special
    ranges[picks] = rng.choice(_SPECIAL, int(picks.sum()))
    inc = 2.0 * math.pi / max(n, 2) * (0.5 if n > 2 and seed % 2 else 1.0)
    scan = LaserScan(ranges, angle_min=angle_min, angle_increment=inc, range_min=0.05,
                     range_max=3.5)  # fmt: skip
    want = _want(scan, k_rep, d0)
    got = repulsive_force_from_scan(scan, k_rep=k_rep, influence_radius=d0)
    assert got.tobytes() == want
    # The subclass path (numba's dispatcher) and the compiled entry, called bare.
    sub = _SubScan(ranges, angle_min=angle_min, angle_increment=inc, range_min=0.05,
                   range_max=3.5)  # fmt: skip
    assert repulsive_force_from_scan(sub, k_rep=k_rep, influence_radius=d0).tobytes() == want
    table = _beam_directions(scan)
    args = (scan.ranges, table, scan.range_min, scan.range_max, k_rep, d0, MIN_DISTANCE)
    for kernel in (khatib_beam_force_into, khatib_entry()):
        out = np.full(2, np.nan)
        kernel(*args, out)
        assert out.tobytes() == want


def test_table_rows_are_the_old_tables() -> None:
    """Row 0 is ``np.cos`` of the angles and row 1 ``np.sin``, bit for bit; one
    read-only C-contiguous array, shared by every call with the same geometry."""
    for n in (1, 2, 7, 360, 1081):
        scan = LaserScan(np.ones(n), angle_min=-2.0, angle_increment=4.0 / n, range_min=0.1,
                         range_max=5.0)  # fmt: skip
        table = _beam_directions(scan)
        angles = scan.angles()
        assert table.shape == (2, n) and table.dtype == np.float64
        assert table.flags.c_contiguous and not table.flags.writeable
        assert table[0].tobytes() == np.cos(angles).tobytes()
        assert table[1].tobytes() == np.sin(angles).tobytes()
        assert _beam_directions(scan) is table
        cos_t, sin_t = _beam_table(scan)
        assert cos_t.base is table and sin_t.base is table
        assert not cos_t.flags.writeable and not sin_t.flags.writeable


def test_inputs_unchanged_and_table_not_writable_through_result() -> None:
    scan = LaserScan(np.linspace(0.2, 2.0, 50), angle_min=-1.0, angle_increment=0.04,
                     range_min=0.1, range_max=5.0)  # fmt: skip
    table: Any = _beam_directions(scan)
    before = table.copy()
    ranges = scan.ranges.copy()
    force = repulsive_force_from_scan(scan, k_rep=2.0, influence_radius=1.5)
    force[:] = 0.0
    np.testing.assert_array_equal(table, before)
    np.testing.assert_array_equal(scan.ranges, ranges)
    assert _want(scan, 2.0, 1.5) == repulsive_force_from_scan(
        scan, k_rep=2.0, influence_radius=1.5
    ).tobytes()
