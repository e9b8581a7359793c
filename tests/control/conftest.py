"""Closed-loop fixtures for the path trackers: analytic paths and a 20 Hz loop.

The loop moves the robot with :func:`navkit.geometry.integrate` (exact SE(2)
integration of each command held for ``dt``), so the trackers are tested
against perfect kinematics; cross-track errors are measured with shapely
against the path's polyline.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest
from shapely.geometry import LineString, Point

from navkit.geometry import Pose2D, integrate


def straight_path(length: float = 4.0, n: int = 81) -> np.ndarray:
    """``(0, 0) → (length, 0)`` with ``n`` points."""
    return np.column_stack([np.linspace(0.0, length, n), np.zeros(n)])


def circle_path(radius: float = 1.0, n: int = 201) -> np.ndarray:
    """A full counter-clockwise circle from ``(0, 0)`` heading +x, centre ``(0, radius)``."""
    t = np.linspace(0.0, 2.0 * math.pi, n)
    return np.column_stack([radius * np.sin(t), radius * (1.0 - np.cos(t))])


def right_angle_path() -> np.ndarray:
    """``(0, 0) → (2, 0) → (2, 2)``: a 90° left turn."""
    return np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]])


def s_curve_path(radius: float = 1.0, n: int = 50) -> np.ndarray:
    """A left then a right quarter circle of ``radius``, then 1 m straight: an S."""
    t = np.linspace(0.0, math.pi / 2, n)
    left = np.column_stack([radius * np.sin(t), radius * (1.0 - np.cos(t))])
    right = np.column_stack([2 * radius - radius * np.cos(t), radius + radius * np.sin(t)])
    return np.vstack([left, right[1:], [[2 * radius + 1.0, 2 * radius]]])


PATHS: dict[str, Callable[[], np.ndarray]] = {
    "straight": straight_path,
    "circle": circle_path,
    "right_angle": right_angle_path,
    "s_curve": s_curve_path,
}


@dataclass(frozen=True)
class Run:
    """A closed-loop run: poses (M+1, 3), commands (M, 3), phases, cross-track error."""

    poses: np.ndarray
    commands: np.ndarray
    phases: list[str]
    cross_track: np.ndarray
    done: bool
    path: np.ndarray

    def goal_error(self) -> float:
        g = self.path[-1]
        return math.hypot(self.poses[-1, 0] - g[0], self.poses[-1, 1] - g[1])

    def after(self, x_min: float | None = None, fraction: float | None = None) -> np.ndarray:
        """Cross-track errors once settled: where x >= x_min, or after a fraction of the run."""
        if x_min is not None:
            return self.cross_track[self.poses[:, 0] >= x_min]
        assert fraction is not None
        return self.cross_track[int(len(self.cross_track) * fraction):]


def run_tracker(
    tracker: Any,
    path: np.ndarray,
    start: Pose2D | tuple[float, float, float],
    *,
    dt: float = 0.05,
    t_max: float = 120.0,
    goal_yaw: float | None = None,
) -> Run:
    """Give ``path`` to ``tracker`` and close the loop until ``done`` or ``t_max``."""
    tracker.set_path(path, goal_yaw=goal_yaw)
    pose = start if isinstance(start, Pose2D) else Pose2D(*start)
    poses = [pose]
    commands = []
    phases = []
    for _ in range(int(t_max / dt)):
        cmd = tracker.step(pose, dt)
        if tracker.done:
            break
        commands.append((cmd.vx, cmd.vy, cmd.omega))
        phases.append(tracker.phase)
        pose = integrate(pose, cmd, dt)
        poses.append(pose)
    xy = np.array([[p.x, p.y, p.theta] for p in poses])
    line = LineString(path) if len(path) > 1 else Point(path[0])
    cte = np.array([line.distance(Point(x, y)) for x, y in xy[:, :2]])
    return Run(
        poses=xy,
        commands=np.array(commands).reshape(-1, 3),
        phases=phases,
        cross_track=cte,
        done=bool(tracker.done),
        path=np.asarray(path, dtype=float),
    )


@pytest.fixture(scope="session")
def closed_loop() -> Callable[..., Run]:
    """:func:`run_tracker`."""
    return run_tracker


@pytest.fixture(scope="session")
def analytic_paths() -> dict[str, Callable[[], np.ndarray]]:
    """Builders of the straight line, circle, right angle and S-curve paths."""
    return PATHS
