"""The beam tables' cache keys -0.0 and 0.0 together, and no force can tell (review 54, FOUND8).

The repulsion sums over a scan (``repulsive_force_from_scan``,
``piecewise_repulsive_force_from_scan``, with or without a mount) share one
table of beam cosines and sines per ``(beam count, angle_min,
angle_increment)``; ``-0.0 == 0.0`` and they hash alike, so a scan with
``angle_min = -0.0`` uses the table of one with ``0.0`` when that came first,
and the other way round. The tables differ: with a negative increment the first
angle is ``-0.0 + 0 * inc = -0.0`` for the one and ``+0.0`` for the other, and
its sine has that sign (a zero increment is refused, so no other angle is a
zero). No force differs, bit for bit, sign of zero included: the kernels
start each sum at +0.0 and subtract products from it, and in round-to-nearest
``+0.0 - (±0.0)`` is +0.0 and ``x - (±0.0)`` is ``x``; a mounted beam's end
point ``mount + r·R·(cos, sin)`` may carry the zero's sign into ``px`` or ``py``,
but those enter the sums only through such products and ``hypot``. Found, not
a defect: the cache is left keyed as it is, and these tests hold it to that.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import navkit.planning.reactive._scan_repulsion as repulsion
from navkit.mapping import LaserScan
from navkit.planning import piecewise_repulsive_force_from_scan, repulsive_force_from_scan

MOUNTS: list[Any] = [
    None,
    (0.0, 0.0, 0.0),
    (-0.0, -0.0, 0.0),
    (0.0, 0.0, 0.5),
    (0.1, 0.0, 0.0),
    (0.1, -0.0, 0.0),
    (-0.0, 0.1, 0.0),
    (-0.0, -0.1, -0.0),
    (0.2, -0.3, 2.0),
]


def _empty_caches(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(repulsion, "_TABLES", {})
    monkeypatch.setattr(repulsion, "_LAST", (0.0, 0.0, 0, np.empty((2, 0))))
    monkeypatch.setattr(repulsion, "_ROWS", (np.empty((2, 0)), np.empty(0), np.empty(0)))


def _scan(ranges: list[float], angle_min: float, increment: float) -> LaserScan:
    return LaserScan(
        ranges, angle_min=angle_min, angle_increment=increment, range_min=0.05, range_max=4.0
    )


def _forces(scan: LaserScan) -> list[bytes]:
    out = []
    for mount in MOUNTS:
        out.append(
            repulsive_force_from_scan(scan, k_rep=0.5, influence_radius=1.5, mount=mount).tobytes()
        )
        out.append(
            piecewise_repulsive_force_from_scan(
                scan, delta=2.0, beta=1.5, obstacle_radius=0.3, spread=1.2, mount=mount
            ).tobytes()
        )
    return out


def test_the_tables_differ_in_the_sign_of_the_first_sine(monkeypatch: pytest.MonkeyPatch) -> None:
    tables = []
    for angle_min in (0.0, -0.0):
        _empty_caches(monkeypatch)
        tables.append(repulsion._beam_directions(_scan([1.0, 1.0], angle_min, -0.01)))
    assert np.signbit(tables[1][1, 0]) and not np.signbit(tables[0][1, 0])
    assert tables[0].tobytes() != tables[1].tobytes()


ranges_st = st.lists(
    st.one_of(st.floats(0.0, 5.0), st.sampled_from([0.0, 0.3, 1.0, 4.0, np.inf, np.nan])),
    min_size=1,
    max_size=6,
)


@settings(max_examples=60, deadline=None)
@given(
    ranges=ranges_st,
    increment=st.sampled_from([-0.01, -0.5, -1e-300, 0.01, 1e-300]),
    first=st.booleans(),
)
def test_a_force_is_the_same_whichever_zero_built_the_table(
    ranges: list[float], increment: float, first: bool
) -> None:
    with pytest.MonkeyPatch.context() as monkeypatch:
        signs = (0.0, -0.0) if first else (-0.0, 0.0)
        _empty_caches(monkeypatch)
        cold = _forces(_scan(ranges, signs[0], increment))
        _empty_caches(monkeypatch)
        _forces(_scan(ranges, signs[1], increment))  # its table is cached first
        warm = _forces(_scan(ranges, signs[0], increment))
        assert warm == cold
