"""Controllers far from the origin: the same commands as at the origin, translated.

Outdoor robots run in UTM coordinates (x, y ~ 5e5 .. 5e6 m). The offsets below
are powers of two and the path and poses multiples of 2**-12 m, so every
translated coordinate is exact: the relative geometry is identical, and any
difference in the commands is rounding inside the controller. A controller that
subtracts after a transform (squares of absolute coordinates, an absolute
lookahead point fed into a curvature) would be off by 1e-3 or more at 4e6 m; the
commands agree to the rounding of one coordinate (about 1e-9).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from navkit.control import (
    FollowTheCarrot,
    OnOffTracker,
    PotentialFieldController,
    RegulatedPurePursuit,
)
from navkit.geometry import Pose2D, integrate

Q = 2.0**-12
OFFSETS = [(524288.0, 4194304.0), (-4194304.0, 524288.0)]
DT = 0.05


def _path() -> np.ndarray:
    s = np.linspace(0.0, 12.0, 241)
    return np.round(np.column_stack((s, 2.0 * np.sin(s / 3.0))) / Q) * Q


def _poses(path: np.ndarray, n: int = 120) -> list[Pose2D]:
    """A closed-loop run at the origin, its positions snapped to the 2**-12 m lattice."""
    tracker = FollowTheCarrot()
    tracker.set_path(path)
    pose = Pose2D(-0.3, 0.2, 0.4)
    out = []
    for _ in range(n):
        pose = Pose2D(round(pose.x / Q) * Q, round(pose.y / Q) * Q, pose.theta)
        out.append(pose)
        pose = integrate(pose, tracker.step(pose, DT), DT)
    return out


def _commands(
    make: Any, path: np.ndarray, poses: list[Pose2D], off: tuple[float, float]
) -> tuple[np.ndarray, float]:
    tracker = make()
    tracker.set_path(path + np.array(off), goal_yaw=1.0)
    cmds = []
    for p in poses:
        cmd = tracker.step(Pose2D(p.x + off[0], p.y + off[1], p.theta), DT)
        cmds.append((cmd.vx, cmd.vy, cmd.omega))
    return np.array(cmds), tracker.progress


@pytest.mark.parametrize("off", OFFSETS)
@pytest.mark.parametrize(
    "make",
    [
        FollowTheCarrot,
        lambda: FollowTheCarrot(drive="omni"),
        OnOffTracker,
        RegulatedPurePursuit,
        lambda: RegulatedPurePursuit(drive="omni"),
    ],
    ids=["carrot", "carrot-omni", "on-off", "rpp", "rpp-omni"],
)
def test_trackers_are_translation_equivariant_at_utm_coordinates(
    make: Any, off: tuple[float, float]
) -> None:
    path = _path()
    poses = _poses(path)
    near, progress_near = _commands(make, path, poses, (0.0, 0.0))
    far, progress_far = _commands(make, path, poses, off)
    assert np.abs(near).max() > 0.1  # the run does steer
    np.testing.assert_allclose(far, near, rtol=0.0, atol=1e-7)
    assert progress_far == pytest.approx(progress_near, abs=1e-7)


@pytest.mark.parametrize("drive", ["omni", "diff"])
@pytest.mark.parametrize("off", OFFSETS)
def test_potential_field_controller_is_translation_equivariant_at_utm_coordinates(
    drive: str, off: tuple[float, float]
) -> None:
    rng = np.random.default_rng(7)
    obstacles = np.round(rng.uniform(-2.0, 2.0, (30, 2)) / Q) * Q
    shift = np.array(off)
    for _ in range(40):
        x, y, gx, gy = (np.round(rng.uniform(-2.5, 2.5, 4) / Q) * Q).tolist()
        theta = float(rng.uniform(-math.pi, math.pi))
        near = PotentialFieldController(drive=drive)  # type: ignore[arg-type]
        far = PotentialFieldController(drive=drive)  # type: ignore[arg-type]
        for _ in range(3):  # the state (velocity, PID) carries over between steps
            a = near.step((x, y, theta), (gx, gy, 0.5), dt=DT, obstacles=obstacles)
            b = far.step(
                (x + off[0], y + off[1], theta),
                (gx + off[0], gy + off[1], 0.5),
                dt=DT,
                obstacles=obstacles + shift,
            )
            assert b.as_array() == pytest.approx(a.as_array(), abs=1e-9)
