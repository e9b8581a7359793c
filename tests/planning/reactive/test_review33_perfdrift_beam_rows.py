"""``_beam_table`` keeps the rows of the last table it sliced (review 33, PERFDRIFT).

Slicing the (2, N) beam table anew cost ``piecewise_repulsive_force_from_scan``
two array views per call (7-9 % of its time on 360 beams since session 27); the rows
are now kept with the table they came from. These tests check that a kept row
never outlives its table: scans of other geometries, alternating or after the
table cache was cleared, get their own directions and the same forces, bit for
bit, as separate cosine and sine arrays computed afresh.
"""

from __future__ import annotations

import math

import numpy as np

from navkit.mapping import LaserScan
from navkit.planning import piecewise_repulsive_force_from_scan
from navkit.planning.reactive import _scan_repulsion
from navkit.planning.reactive._scan_repulsion import _beam_directions, _beam_table
from navkit.planning.reactive._scan_repulsion_kernels import piecewise_beam_force


def _scan(n: int, angle_min: float, seed: int) -> LaserScan:
    ranges = np.random.default_rng(seed).uniform(0.05, 2.5, n)
    return LaserScan(ranges, angle_min=angle_min, angle_increment=2.0 * math.pi / n,
                     range_min=0.1, range_max=3.0)  # fmt: skip


def _want(scan: LaserScan) -> bytes:
    """The force from freshly computed cosine and sine arrays (no cached table)."""
    angles = scan.angles()
    fx, fy = piecewise_beam_force(
        scan.ranges, np.cos(angles), np.sin(angles), scan.range_min, scan.range_max,
        1.0, 1.0, 0.0, 1.0,
    )  # fmt: skip
    return np.array([fx, fy]).tobytes()


def _check(scan: LaserScan) -> None:
    angles = scan.angles()
    cos_t, sin_t = _beam_table(scan)
    assert cos_t.tobytes() == np.cos(angles).tobytes()
    assert sin_t.tobytes() == np.sin(angles).tobytes()
    assert cos_t.base is _beam_directions(scan) and sin_t.base is cos_t.base
    assert piecewise_repulsive_force_from_scan(scan).tobytes() == _want(scan)


def test_alternating_geometries_get_their_own_rows() -> None:
    # Same beam count, other angle_min: only the rows' values tell them apart.
    a, b, c = _scan(360, -math.pi, 1), _scan(360, -3.0, 2), _scan(181, -1.5, 3)
    for scan in (a, b, a, c, b, c, a, a, b):
        _check(scan)


def test_rows_follow_a_rebuilt_table() -> None:
    a = _scan(360, -2.5, 4)
    _check(a)
    old_rows = _beam_table(a)
    # More geometries than the cache holds: it is cleared and a's table rebuilt.
    for k in range(_scan_repulsion._TABLES_MAX + 1):
        _check(_scan(10 + k, -1.0, k))
    _check(a)
    cos_t, _ = _beam_table(a)
    assert cos_t.base is not old_rows[0].base
    assert cos_t.tobytes() == old_rows[0].tobytes()


def test_same_geometry_reuses_the_rows() -> None:
    a = _scan(360, -math.pi, 5)
    first = _beam_table(a)
    again = _beam_table(_scan(360, -math.pi, 6))
    assert again[0] is first[0] and again[1] is first[1]
