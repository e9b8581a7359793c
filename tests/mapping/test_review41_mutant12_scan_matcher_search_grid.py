"""The correlative pre-search's grid of poses is the documented one (MUTANT12).

Mutation review 41: ``_MAX_SEARCH_STEPS`` at 359 instead of 360 survived; no test
looked at the grid of poses the pre-search evaluates, only at where the match ends
(Gauss–Newton then refines from any nearby grid point to the same pose). The
documented grid (``ScanMatcher``'s ``search_distance, search_angle``): translations
one coarsest cell apart out to the window, rotations that move the far points
(90th percentile of the ranges) by at most half a cell, the fewest such steps,
at most 360 each way; more than 2**25 poses spread the translations to fit.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from room_scans import room_scan

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid, ScanMatcher, _scan_matcher, integrate_scan

_MAX_POSES = 2**25


def _room() -> OccupancyGrid:
    grid = OccupancyGrid.empty(width=10.0, height=10.0, resolution=0.05, origin=(-5.0, -5.0, 0.0))
    integrate_scan(grid, room_scan(0.0, 0.0), (0.0, 0.0, 0.0), hit=2.2, miss=-0.4)
    return grid


def _grid_of(
    monkeypatch: pytest.MonkeyPatch, matcher: ScanMatcher, *, call_through: bool = True
) -> dict[str, Any]:
    seen: dict[str, Any] = {}
    real = _scan_matcher.correlative_search

    def spy(*args: Any) -> Any:
        seen.update(
            res=args[4], points=np.array(args[5]), steps_xy=args[7], step_xy=args[8],
            steps_theta=args[9], step_theta=args[10],
        )  # fmt: skip
        return real(*args) if call_through else None

    monkeypatch.setattr(_scan_matcher, "correlative_search", spy)
    matcher.match(_room(), room_scan(0.05, -0.05, 0.02), Pose2D(0.0, 0.0, 0.0))
    assert seen, "the pre-search was not run"
    return seen


def _reach(points: np.ndarray) -> float:
    return float(np.percentile(np.hypot(points[:, 0], points[:, 1]), 90.0))


@pytest.mark.parametrize("angle", [0.05, 0.3, 1.0])
@pytest.mark.parametrize("levels", [1, 3])
def test_rotation_steps_move_the_far_points_by_at_most_half_a_cell(
    monkeypatch: pytest.MonkeyPatch, angle: float, levels: int
) -> None:
    seen = _grid_of(
        monkeypatch, ScanMatcher(levels=levels, search_distance=0.1, search_angle=angle)
    )
    res, n, step = seen["res"], seen["steps_theta"], seen["step_theta"]
    assert res == pytest.approx(0.05 * 2 ** (levels - 1), rel=1e-12)  # the coarsest level
    # The points are the scan's, in the sensor frame.
    assert np.array_equal(
        seen["points"], _scan_matcher.scan_points(room_scan(0.05, -0.05, 0.02), None)
    )
    reach = _reach(seen["points"])
    assert step * n == pytest.approx(angle, rel=1e-12)  # out to the window exactly
    assert step * reach <= 0.5 * res * (1 + 1e-12)  # half a cell at the far points
    # The fewest steps: one fewer would move them further than that (or below 0.25°).
    fewer = angle / (n - 1) if n > 1 else math.inf
    assert fewer * reach > 0.5 * res or fewer < math.radians(0.25)


def test_rotation_steps_are_at_most_360_each_way(monkeypatch: pytest.MonkeyPatch) -> None:
    # Far points 100 coarse cells away: half a cell is 0.29°, π would need 628 steps.
    seen = _grid_of(monkeypatch, ScanMatcher(levels=1, search_distance=0.05, search_angle=math.pi))
    assert 0.5 * seen["res"] / _reach(seen["points"]) < math.pi / 360
    assert seen["steps_theta"] == 360
    assert seen["step_theta"] == pytest.approx(math.pi / 360, rel=1e-12)


@pytest.mark.parametrize("distance", [0.05, 0.12, 0.3])
def test_translations_are_one_coarsest_cell_apart_out_to_the_window(
    monkeypatch: pytest.MonkeyPatch, distance: float
) -> None:
    seen = _grid_of(monkeypatch, ScanMatcher(levels=2, search_distance=distance, search_angle=0.1))
    res, n = seen["res"], seen["steps_xy"]
    assert seen["step_xy"] == res
    assert (n - 1) * res < distance * (1 - 1e-9) and n * res >= distance * (1 - 1e-9)


def test_a_grid_beyond_the_budget_spreads_its_translations(monkeypatch: pytest.MonkeyPatch) -> None:
    matcher = ScanMatcher(levels=1, search_distance=100.0, search_angle=math.pi)
    seen = _grid_of(monkeypatch, matcher, call_through=False)
    n, rotations = seen["steps_xy"], 2 * seen["steps_theta"] + 1
    assert seen["steps_theta"] == 360  # the rotations are kept
    assert (2 * n + 1) ** 2 * rotations <= _MAX_POSES < (2 * n + 3) ** 2 * rotations
    assert seen["step_xy"] * n == pytest.approx(100.0, rel=1e-12)
