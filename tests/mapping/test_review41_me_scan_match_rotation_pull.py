"""ScanMatcher's rotation pull balances the map where the documented cost is stationary.

The matcher minimises ``mean (1 - M)² + translation_weight² |t - t₀|² +
rotation_weight² (θ - θ₀)²``. Mutation review 41 (MUTANT12) found that
``rotation_weight + rotation_weight`` in place of its square survived every
test: none checked where the rotation pull settles against the map. Here the
map is smooth (walls as Gaussian ridges several cells wide, so the bilinear
interpolant's kinks at cell edges are small), the guess is turned away from
the true heading, and at the match the cost's θ derivative must vanish: the
map's part (``-2/m Σ J_θ (1 - M)``, from the kernel's exact gradient) equals
minus the pull's ``2 rotation_weight² (θ - θ₀)``. A pull of ``2 w`` instead of
``w²`` settles elsewhere: the two parts then differ by a factor ``w / 2``
(1/2 and 3/2 for the weights below).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, OccupancyGrid, ScanMatcher
from navkit.mapping._scan_matcher import FLOOR, scan_points
from navkit.mapping._scan_matcher_kernels import accumulate

_RES = 0.05


def _room() -> tuple[OccupancyGrid, LaserScan]:
    """A 6 m × 4 m room seen from its centre, its walls ridges about 0.25 m wide."""
    angles = np.linspace(-math.pi, math.pi, 180, endpoint=False)
    with np.errstate(divide="ignore"):
        ranges = np.minimum(3.0 / np.abs(np.cos(angles)), 2.0 / np.abs(np.sin(angles)))
    scan = LaserScan(
        ranges, angle_min=-math.pi, angle_increment=2 * math.pi / 180,
        range_min=0.1, range_max=10.0,
    )  # fmt: skip
    rows, cols = np.mgrid[0:120, 0:160]
    x = -4.0 + (cols + 0.5) * _RES
    y = -3.0 + (rows + 0.5) * _RES
    wall = np.minimum(np.abs(np.abs(x) - 3.0), np.abs(np.abs(y) - 2.0))
    probabilities = 0.05 + 0.9 * np.exp(-((wall / 0.25) ** 2))
    origin = (-4.0, -3.0, 0.0)
    return OccupancyGrid.from_probabilities(probabilities, resolution=_RES, origin=origin), scan


@pytest.mark.parametrize("weight", [1.0, 3.0])
@pytest.mark.parametrize("turned", [0.05, 0.08, -0.04])
def test_the_rotation_pull_balances_the_map_at_the_match(weight: float, turned: float) -> None:
    grid, scan = _room()
    matcher = ScanMatcher(
        levels=1, rotation_weight=weight, translation_weight=1.0,
        tolerance=1e-9, max_iterations=1000,
    )  # fmt: skip
    pose = matcher.match(grid, scan, Pose2D(0.0, 0.0, turned)).pose
    points = scan_points(scan, None)
    hessian, gradient = np.empty((3, 3)), np.empty(3)
    o = grid.origin
    accumulate(
        grid._logodds, o.x, o.y, o.theta, grid.resolution, points,
        pose.x, pose.y, pose.theta, FLOOR, hessian, gradient,
    )  # fmt: skip
    map_part = -2.0 * gradient[2] / points.shape[0]
    pull_part = 2.0 * weight * weight * (pose.theta - turned)
    # The pull moved the match off the true heading (0) and off the guess.
    assert 0.1 * abs(turned) < abs(pose.theta) < 0.9 * abs(turned)
    assert -map_part / pull_part == pytest.approx(1.0, abs=0.1)
