"""Subclasses of the mapping records copy and pickle whole, with read-only arrays."""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, LocalGrid, ScanMatchResult

COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    lambda obj: pickle.loads(pickle.dumps(obj)),
]


class TaggedScan(LaserScan):
    __slots__ = ("frame",)


@dataclass(frozen=True, slots=True)
class NamedGrid(LocalGrid):
    name: str = ""


class TaggedResult(ScanMatchResult):
    pass


@pytest.mark.parametrize("make_copy", COPIES)
def test_scan_subclass(make_copy: Callable[[Any], Any]) -> None:
    scan = TaggedScan(
        [1.0, 2.0], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0,
        intensities=[3.0, 4.0],
    )
    object.__setattr__(scan, "frame", "laser")
    out = make_copy(scan)
    assert type(out) is TaggedScan and out.frame == "laser"
    np.testing.assert_array_equal(out.ranges, scan.ranges)
    assert out.intensities is not None
    assert not out.ranges.flags.writeable and not out.intensities.flags.writeable


@pytest.mark.parametrize("make_copy", COPIES)
def test_local_grid_dataclass_subclass(make_copy: Callable[[Any], Any]) -> None:
    grid = NamedGrid(np.eye(3, dtype=bool), resolution=0.1, half_width=0.1, name="g")
    out = make_copy(grid)
    assert type(out) is NamedGrid and out.name == "g"
    np.testing.assert_array_equal(out.occupied, grid.occupied)
    assert not out.occupied.flags.writeable


@pytest.mark.parametrize("make_copy", COPIES)
def test_match_result_subclass(make_copy: Callable[[Any], Any]) -> None:
    result = TaggedResult(Pose2D(1.0, 2.0, 0.5), np.eye(3), 4, 0.9, True, "converged")
    object.__setattr__(result, "note", [7])
    out = make_copy(result)
    assert type(out) is TaggedResult and out.note == [7]
    assert out.pose == result.pose
    np.testing.assert_array_equal(out.covariance, result.covariance)
    assert not out.covariance.flags.writeable
