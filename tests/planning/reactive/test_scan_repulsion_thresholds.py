"""Per-beam piecewise repulsion at ranges exactly on its thresholds.

The scan kernel compares each range itself with ``r`` and ``s + r``; the point
field on ``scan.to_points()`` compares ``hypot(ρ cos θ, ρ sin θ)``, which can
round a range equal to ``r`` to just below it. The two then differ by exactly the
jump ``δ - β·s`` on those beams, and nowhere else.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.mapping import LaserScan
from navkit.planning import PiecewiseRepulsion, piecewise_repulsive_force_from_scan


def ring(rho: float, n: int = 360, range_min: float = 0.0, range_max: float = 10.0) -> LaserScan:
    return LaserScan(np.full(n, rho), angle_min=-math.pi, angle_increment=2.0 * math.pi / n,
                     range_min=range_min, range_max=range_max)


def per_beam(scan: LaserScan, magnitude: float) -> np.ndarray:
    """Force of every valid beam pushing with ``magnitude``, summed in beam order."""
    angles = scan.angles()[scan.valid_mask()]
    return -magnitude * np.array([np.sum(np.cos(angles)), np.sum(np.sin(angles))])


@settings(max_examples=50, deadline=None)
@given(
    st.one_of(st.sampled_from([0.3, 0.5, 1.0 / 3.0, 0.7, 1.0]), st.floats(1e-3, 5.0)),
    st.one_of(st.sampled_from([0.1, 0.2, 1.0 / 3.0]), st.floats(1e-3, 5.0)),
    st.floats(0.1, 10.0),
    st.floats(0.1, 10.0),
    st.integers(1, 90),
    st.floats(-math.pi, math.pi),
)
def test_ranges_on_the_thresholds_differ_only_by_the_jump(
    r: float, s: float, delta: float, beta: float, n: int, angle_min: float
) -> None:
    reach = s + r
    inc = 2.0 * math.pi / max(n, 2) / 2.0
    for rho in (r, reach, math.nextafter(r, 0.0), math.nextafter(reach, math.inf)):
        scan = LaserScan(np.full(n, rho), angle_min=angle_min, angle_increment=inc,
                         range_min=0.0, range_max=10.0 + reach)
        got = piecewise_repulsive_force_from_scan(scan, delta=delta, beta=beta,
                                                  obstacle_radius=r, spread=s)
        # The documented law applied to the range itself.
        if rho < r:
            magnitude = delta
        elif rho <= reach:
            magnitude = beta * (reach - rho)
        else:
            magnitude = 0.0
        scale = (delta + beta * s) * n
        np.testing.assert_allclose(got, per_beam(scan, magnitude), rtol=0, atol=1e-13 * scale)
        points = scan.to_points()
        field = PiecewiseRepulsion(points, delta=delta, beta=beta, obstacle_radius=r, spread=s)
        want = field.force([0.0, 0.0])[0]
        # Beams whose point the field sees on the other side of r get the other branch.
        seen = np.hypot(points[:, 0], points[:, 1])
        crossed = (seen < r) != (rho < r)
        seen_magnitude = np.where(seen < r, delta, beta * np.clip(reach - seen, 0.0, s))
        change = (seen_magnitude - magnitude)[crossed]
        angles = scan.angles()[crossed]
        explained = got - np.array([np.sum(change * np.cos(angles)),
                                    np.sum(change * np.sin(angles))])
        np.testing.assert_allclose(want, explained, rtol=0, atol=1e-12 * scale)


test_ranges_on_the_thresholds_differ_only_by_the_jump_thoroughly = slow_twin(
    test_ranges_on_the_thresholds_differ_only_by_the_jump, max_examples=200
)


def test_kernel_at_each_threshold() -> None:
    # r = 0.3, s = 0.5: the push is δ below r, β·s at r, 0 at r + s; range_min is a
    # valid reading and range_max is "no return".
    def push(rho: float, range_min: float = 0.0, range_max: float = 9.0) -> float:
        scan = LaserScan(np.array([rho]), angle_min=0.0, angle_increment=0.1,
                         range_min=range_min, range_max=range_max)
        force = piecewise_repulsive_force_from_scan(scan, delta=5.0, beta=2.0,
                                                    obstacle_radius=0.3, spread=0.5)
        return -float(force[0])

    assert push(0.3) == 1.0
    assert push(math.nextafter(0.3, 0.0)) == 5.0
    assert push(0.8) == 0.0
    assert push(0.3, range_min=0.3) == 1.0
    assert push(0.3, range_max=0.3) == 0.0
    # On a full ring at r the point field puts some beams just inside r.
    scan = ring(0.3)
    points = scan.to_points()
    assert np.any(np.hypot(points[:, 0], points[:, 1]) < 0.3)
    got = piecewise_repulsive_force_from_scan(scan, delta=5.0, beta=2.0, obstacle_radius=0.3,
                                              spread=0.5)
    np.testing.assert_allclose(got, per_beam(scan, 1.0), atol=1e-12)
    field = PiecewiseRepulsion(points, delta=5.0, beta=2.0, obstacle_radius=0.3, spread=0.5)
    assert np.linalg.norm(field.force([0.0, 0.0])[0] - per_beam(scan, 1.0)) > 1e-3
