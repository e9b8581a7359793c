"""The reference path of a run: its checks and the cross-track error."""

from __future__ import annotations

import numpy as np
import pytest
from shapely.geometry import LineString, Point, box

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.planning import Path2D
from navkit.sim import Observation, Robot, Simulation, World

WORLD = World(box(-5.0, -5.0, 5.0, 5.0).exterior)
ROBOT = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)


def _forward(obs: Observation) -> Twist2D:
    return Twist2D(0.5, 0.0, 0.2)


@pytest.mark.parametrize("half", [1e3, 1e6])
def test_cross_track_of_a_long_reference_path_matches_shapely(half: float) -> None:
    path = np.array([[-half, 0.1], [half, 0.1]])
    trace = Simulation(
        WORLD, ROBOT, _forward, start=(0.0, 0.0, 0.0), reference_path=path, duration=2.0
    ).run()
    line = LineString(path)
    expected = [line.distance(Point(x, y)) for x, y in trace.poses[:, :2]]
    assert trace.metrics.cross_track_max == pytest.approx(max(expected), abs=1e-9)
    assert trace.metrics.cross_track_mean == pytest.approx(np.mean(expected), abs=1e-9)


@pytest.mark.parametrize("as_path", [False, True])
@pytest.mark.parametrize("far", [1.0000001e12, 1e200])
def test_reference_paths_too_far_out_are_refused(as_path: bool, far: float) -> None:
    # Squared leg lengths overflowed past 1e154: the robot on the path was put 1e200 m off it.
    points = np.array([[-far, 0.0], [far, 0.0]])
    ref = Path2D(points, "world", 0.0, 2.0 * far, 0) if as_path else points
    with pytest.raises(ValueError, match="reference_path"):
        Simulation(WORLD, ROBOT, _forward, start=(0.0, 0.0, 0.0), reference_path=ref)
