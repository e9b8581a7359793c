"""Mapping branches the default suite never ran (coverage review, session 30).

Refusals users meet (masks of the wrong shape, a hand-built scan-match result
with a bad field, scan-matching levels that are not a short sequence of grids)
and results at the edge of the map (``cells_near`` of points
whose discs only graze the map's corner), each checked for its message, its
result and the caller's arrays left as they were.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, OccupancyGrid, ScanMatcher, ScanMatchResult


@pytest.mark.parametrize(
    ("occupied", "shape"),
    [
        (np.zeros(3, dtype=bool), "(3,)"),
        (np.zeros((0, 3), dtype=bool), "(0, 3)"),
        (np.zeros((2, 2, 2), dtype=bool), "(2, 2, 2)"),
    ],
)
def test_from_occupancy_refuses_a_mask_that_is_not_a_2d_grid(
    occupied: np.ndarray, shape: str
) -> None:
    with pytest.raises(ValueError) as info:
        OccupancyGrid.from_occupancy(occupied, resolution=1.0)
    assert str(info.value) == (f"occupied must be a non-empty 2-D (rows, cols) array, got {shape}")


def test_from_occupancy_refuses_an_unknown_mask_of_another_shape() -> None:
    occupied = np.zeros((2, 3), dtype=bool)
    unknown = np.zeros((3, 2), dtype=bool)
    with pytest.raises(
        ValueError,
        match=r"^unknown must have the shape of occupied \(2, 3\), "
        r"got \(3, 2\)$",
    ):
        OccupancyGrid.from_occupancy(occupied, resolution=1.0, unknown=unknown)
    with pytest.raises(ValueError, match=r"^unknown must be a non-empty 2-D"):
        OccupancyGrid.from_occupancy(occupied, resolution=1.0, unknown=np.zeros(6, dtype=bool))
    with pytest.raises(TypeError, match=r"^unknown must be a boolean array, got dtype float64"):
        OccupancyGrid.from_occupancy(occupied, resolution=1.0, unknown=np.zeros((2, 3)))
    assert not occupied.any() and not unknown.any()


def test_cells_near_points_whose_discs_miss_the_map_is_empty() -> None:
    grid = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.2)
    # Cell (-1, -1), diagonal to the corner: within a disc's row and column reach
    # (1 cell) but not within its radius, so counted and found empty.
    points = np.array([[-0.1, -0.1], [1.1, 1.1], [-0.1, 1.1], [1.1, -0.1]])
    before = points.copy()
    near = grid.cells_near(points, robot_radius=0.2)
    assert near.shape == (0, 2) and near.dtype == np.int64
    np.testing.assert_array_equal(points, before)
    # Beside an edge (not a corner), or with a disc reaching past the diagonal,
    # the corner cell is near.
    assert grid.cells_near([0.1, -0.1], robot_radius=0.2).tolist() == [[0, 0]]
    assert grid.cells_near([-0.1, -0.1], robot_radius=0.3).tolist() == [[0, 0]]


def test_grid_repr_names_shape_resolution_and_origin() -> None:
    grid = OccupancyGrid.empty(width=1.0, height=0.6, resolution=0.2, origin=(1.0, -2.0, 0.5))
    assert repr(grid) == (
        "OccupancyGrid(<3x5 cells>, resolution=0.2, origin=Pose2D(x=1.0, y=-2.0, theta=0.5))"
    )


def _result(**changes: Any) -> ScanMatchResult:
    fields: dict[str, Any] = {
        "pose": Pose2D(0.0, 0.0, 0.0),
        "covariance": np.eye(3),
        "iterations": 3,
        "score": 0.5,
        "converged": True,
        "reason": "converged",
    }
    fields.update(changes)
    return ScanMatchResult(**fields)


def test_scan_match_result_takes_a_pose_as_numbers() -> None:
    result = _result(pose=[1.0, 2.0, 0.5], converged=np.bool_(False), reason="max_iterations")
    assert result.pose == Pose2D(1.0, 2.0, 0.5)
    assert result.converged is False
    # +inf (an unbounded direction) is a covariance; the record holds a read-only copy.
    given = np.diag([1.0, np.inf, 1.0])
    held = _result(covariance=given).covariance
    np.testing.assert_array_equal(held, given)
    assert not held.flags.writeable and given.flags.writeable


@pytest.mark.parametrize(
    ("changes", "error", "message"),
    [
        (
            {"covariance": np.full((3, 3), np.nan)},
            ValueError,
            r"^covariance must not contain NaN or -inf$",
        ),
        (
            {"covariance": np.diag([1.0, -np.inf, 1.0])},
            ValueError,
            r"^covariance must not contain NaN or -inf$",
        ),
        ({"converged": 1}, TypeError, r"^converged must be a bool, got int$"),
        ({"reason": 3}, TypeError, r"^reason must be a str, got int$"),
        ({"reason": "done"}, ValueError, r"^reason must be one of \('converged', .*got 'done'$"),
    ],
    ids=["nan-covariance", "minus-inf-covariance", "int-converged", "int-reason", "unknown-reason"],
)
def test_scan_match_result_refuses_a_bad_field_naming_it(
    changes: dict[str, Any], error: type[Exception], message: str
) -> None:
    given = {k: v.copy() if isinstance(v, np.ndarray) else v for k, v in changes.items()}
    with pytest.raises(error, match=message):
        _result(**changes)
    for key, value in given.items():
        np.testing.assert_array_equal(changes[key], value)


_GRID = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.1)


@pytest.mark.parametrize(
    ("maps", "error", "message"),
    [
        ("grid", TypeError, r"^maps must be an OccupancyGrid or a sequence of them, got str$"),
        ([], ValueError, r"^maps must hold at least one OccupancyGrid$"),
        ([_GRID] * 17, ValueError, r"^maps must hold at most 16 levels, got 17$"),
        ([_GRID, "x"], TypeError, r"^maps\[1\] must be an OccupancyGrid, got str$"),
    ],
    ids=["str", "empty", "too-many", "not-a-grid"],
)
def test_scan_matcher_refuses_bad_levels_naming_maps(
    maps: Any, error: type[Exception], message: str
) -> None:
    scan = LaserScan([1.0] * 10, angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0)
    with pytest.raises(error, match=message):
        ScanMatcher().match(maps, scan, (1.0, 1.0, 0.0))
