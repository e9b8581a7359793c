"""ScanMapper(pose=): the start pose under the name the odometries and PlanarFusion use.

``start=`` (its name before review 21) keeps working for a release with a
DeprecationWarning pointing at the caller's line, and builds the same mapper.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, ScanMapper, ScanMatcher


def _room_scan() -> LaserScan:
    angles = np.linspace(-math.pi, math.pi, 90, endpoint=False)
    ranges = 2.0 / np.maximum(np.abs(np.cos(angles)), np.abs(np.sin(angles)))
    return LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / 90,
                     range_min=0.1, range_max=10.0)  # fmt: skip


def _run(mapper: ScanMapper) -> ScanMapper:
    scan = _room_scan()
    mapper.update(scan)
    mapper.update(scan, odometry=(0.05, -0.04, 0.03))
    return mapper


def test_pose_sets_the_first_scans_pose_without_warning() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mapper = ScanMapper(resolution=0.1, pose=(1.0, 2.0, 0.5))
        assert mapper.pose == Pose2D(1.0, 2.0, 0.5)
        mapper.update(_room_scan())
    assert mapper.trajectory.tolist() == [[1.0, 2.0, 0.5]]


@settings(max_examples=15, deadline=None)
@given(
    st.floats(-50.0, 50.0),
    st.floats(-50.0, 50.0),
    st.floats(-math.pi, math.pi, exclude_min=True),
)
def test_the_old_name_builds_the_same_mapper(x: float, y: float, theta: float) -> None:
    matcher = ScanMatcher(levels=2)
    new = _run(ScanMapper(resolution=0.2, pose=(x, y, theta), matcher=matcher))
    with pytest.warns(DeprecationWarning, match=r"start is deprecated.*use pose") as caught:
        old = ScanMapper(resolution=0.2, start=(x, y, theta), matcher=matcher)
    assert caught[0].filename == __file__  # the caller's line, not navkit's
    _run(old)
    assert np.array_equal(old.trajectory, new.trajectory)
    assert np.array_equal(old.map.logodds, new.map.logodds)
    assert old.map.origin == new.map.origin


def test_both_names_are_refused() -> None:
    with pytest.raises(TypeError, match="got both pose and its old name start"):
        ScanMapper(pose=(1.0, 0.0, 0.0), start=(2.0, 0.0, 0.0))


@pytest.mark.parametrize("name", ["pose", "start"])
@pytest.mark.parametrize(
    ("value", "error"),
    [((math.nan, 0.0, 0.0), ValueError), ((2e9, 0.0, 0.0), ValueError), ("origin", TypeError)],
)
def test_a_bad_pose_is_refused_under_the_name_written(
    name: str, value: object, error: type[Exception]
) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        with pytest.raises(error, match=rf"^{name}\b"):
            ScanMapper(**{name: value})  # type: ignore[arg-type]
