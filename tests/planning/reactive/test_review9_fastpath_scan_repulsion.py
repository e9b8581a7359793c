"""``repulsive_force_from_scan``: the fast path (exact LaserScan, plain floats) equals the rest.

The fast path takes plain in-range floats without the validators, finds the
beam tables by comparing the last scanner's (angle_min, angle_increment, beam
count) and calls the compiled entry; a LaserScan subclass, NumPy or integer
parameters take the validators and the dispatcher. Both must give the same
force bit for bit and the same errors; scanners that differ only in their beam
count must never share tables.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping import LaserScan
from navkit.planning import KhatibRepulsion, repulsive_force_from_scan


class _SubScan(LaserScan):
    __slots__ = ()


def _scan(cls: Any, ranges: Any, angle_min: float = -math.pi, inc: float = 0.01) -> LaserScan:
    out: LaserScan = cls(
        ranges, angle_min=angle_min, angle_increment=inc, range_min=0.05, range_max=4.0
    )
    return out


def _reference(scan: LaserScan, k: float, d0: float) -> np.ndarray:
    pts = scan.to_points()
    if len(pts) == 0:
        return np.zeros(2)
    force = KhatibRepulsion(pts, k_rep=k, influence_radius=d0).force((0.0, 0.0))
    return np.asarray(force, dtype=np.float64).reshape(2)


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    counts=st.lists(st.integers(1, 40), min_size=2, max_size=6),
    angle_min=st.sampled_from([-math.pi, -1.0, 0.0]),
    inc=st.sampled_from([0.01, math.pi / 40, 2 * math.pi / 41]),  # 40 beams within 2π
    k=st.floats(0.1, 10.0),
    d0=st.floats(0.1, 3.0),
)
def test_scanners_differing_only_in_beam_count_each_get_their_own_tables(
    seed: int, counts: list[int], angle_min: float, inc: float, k: float, d0: float
) -> None:
    rng = np.random.default_rng(seed)
    for n in counts:  # one geometry, beam counts changing from call to call
        ranges = rng.uniform(0.0, 4.5, size=n)
        fast = repulsive_force_from_scan(
            _scan(LaserScan, ranges, angle_min, inc), k_rep=k, influence_radius=d0
        )
        sub = repulsive_force_from_scan(
            _scan(_SubScan, ranges, angle_min, inc), k_rep=k, influence_radius=d0
        )
        assert fast.tobytes() == sub.tobytes()
        np.testing.assert_allclose(
            fast, _reference(_scan(LaserScan, ranges, angle_min, inc), k, d0),
            rtol=1e-9, atol=1e-9 * (1.0 + float(np.abs(fast).max())),
        )


@pytest.mark.parametrize(
    ("k", "d0"),
    [
        (np.float64(0.5), 1.0),
        (0.5, np.float64(1.0)),
        (np.float32(0.5), np.float32(1.0)),
        (1, 2),
        (np.int64(1), np.int32(2)),
    ],
)
def test_other_real_parameter_types_equal_plain_floats(k: Any, d0: Any) -> None:
    scan = _scan(LaserScan, np.linspace(0.1, 3.0, 90))
    got = repulsive_force_from_scan(scan, k_rep=k, influence_radius=d0)
    want = repulsive_force_from_scan(scan, k_rep=float(k), influence_radius=float(d0))
    assert got.tobytes() == want.tobytes()
    assert got.dtype == np.float64 and got.shape == (2,) and got.flags.writeable


def _error(call: Callable[[], Any]) -> tuple[type[BaseException], str]:
    with pytest.raises((TypeError, ValueError)) as info:
        call()
    return type(info.value), str(info.value)


@pytest.mark.parametrize("name", ["k_rep", "influence_radius"])
@pytest.mark.parametrize("bad", [math.nan, math.inf, -1.0, 0.0, 1e-13, 1e13, 2e6])
def test_bad_floats_get_the_validators_error(name: str, bad: float) -> None:
    if name == "influence_radius" and bad in (1e-13,):
        bad = 1e-7  # below its own bound, 1e-6
    scan = _scan(LaserScan, np.linspace(0.1, 3.0, 30))
    sub = _scan(_SubScan, np.linspace(0.1, 3.0, 30))
    if name == "k_rep" and bad == 2e6:
        return  # a valid gain
    plain = _error(lambda: repulsive_force_from_scan(scan, **{name: bad}))
    assert plain == _error(lambda: repulsive_force_from_scan(scan, **{name: np.float64(bad)}))
    assert plain == _error(lambda: repulsive_force_from_scan(sub, **{name: bad}))
    assert name in plain[1]


@pytest.mark.parametrize("name", ["k_rep", "influence_radius"])
@pytest.mark.parametrize("bad", [True, np.bool_(True), "1.0", None, 1 + 0j, [1.0]])
def test_non_numbers_refused(name: str, bad: Any) -> None:
    scan = _scan(LaserScan, np.linspace(0.1, 3.0, 30))
    with pytest.raises(TypeError, match=name):
        repulsive_force_from_scan(scan, **{name: bad})


@pytest.mark.parametrize("bad", [None, np.zeros(3), [0.5, 1.0], "scan", object()])
def test_non_scans_refused(bad: Any) -> None:
    with pytest.raises(TypeError, match="scan"):
        repulsive_force_from_scan(bad)


def test_result_is_fresh_and_the_scan_unchanged() -> None:
    scan = _scan(LaserScan, np.linspace(0.1, 3.0, 60))
    before = scan.ranges.copy()
    a = repulsive_force_from_scan(scan, k_rep=0.5, influence_radius=1.0)
    b = repulsive_force_from_scan(scan, k_rep=0.5, influence_radius=1.0)
    assert a is not b and not np.shares_memory(a, b)
    a[:] = 0.0
    assert b.tobytes() == repulsive_force_from_scan(scan, k_rep=0.5, influence_radius=1.0).tobytes()
    assert scan.ranges.tobytes() == before.tobytes() and not scan.ranges.flags.writeable
