"""Figures of the path trackers on the right-angle and S-curve paths (issue 13).

Runs FollowTheCarrot, OnOffTracker and RegulatedPurePursuit (differential drive,
default settings, 20 Hz, exact SE(2) integration) from a pose 5 cm off each
path and plots the driven trajectories over the path, with the cross-track
error along the way. Writes ``trackers_right_angle.png`` and
``trackers_s_curve.png``.

Usage::

    python docs/figures/trackers.py [OUTPUT_DIR]   # default: this script's folder

Needs matplotlib (``pip install -e ".[plot]"``).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

from navkit.control import FollowTheCarrot, OnOffTracker, RegulatedPurePursuit
from navkit.geometry import Pose2D, integrate

DT = 0.05


def right_angle_path() -> np.ndarray:
    """``(0, 0) → (2, 0) → (2, 2)``."""
    return np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]])


def s_curve_path(radius: float = 1.0, n: int = 50) -> np.ndarray:
    """A left then a right quarter circle of ``radius``, then 1 m straight."""
    t = np.linspace(0.0, math.pi / 2, n)
    left = np.column_stack([radius * np.sin(t), radius * (1.0 - np.cos(t))])
    right = np.column_stack([2 * radius - radius * np.cos(t), radius + radius * np.sin(t)])
    return np.vstack([left, right[1:], [[2 * radius + 1.0, 2 * radius]]])


def cross_track(points_xy: np.ndarray, path: np.ndarray) -> np.ndarray:
    """Distance from each point to the polyline ``path``."""
    a = path[:-1][None, :, :]
    d = (path[1:] - path[:-1])[None, :, :]
    p = points_xy[:, None, :]
    t = np.clip(np.sum((p - a) * d, axis=2) / np.sum(d * d, axis=2), 0.0, 1.0)
    foot = a + t[:, :, None] * d
    out: np.ndarray = np.min(np.hypot(*(p - foot).transpose(2, 0, 1)), axis=1)
    return out


def run(tracker: Any, path: np.ndarray, start: Pose2D, goal_yaw: float) -> np.ndarray:
    """Close the loop until the tracker is done; the poses ``(M, 3)``."""
    tracker.set_path(path, goal_yaw=goal_yaw)
    pose = start
    poses = [pose.as_array()]
    for _ in range(int(120.0 / DT)):
        cmd = tracker.step(pose, DT)
        if tracker.done:
            break
        pose = integrate(pose, cmd, DT)
        poses.append(pose.as_array())
    return np.array(poses)


def figure(name: str, path: np.ndarray, goal_yaw: float, out_dir: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    trackers = {
        "FollowTheCarrot (0.18 m/s)": FollowTheCarrot(),
        "OnOffTracker (0.2 m/s)": OnOffTracker(),
        "RegulatedPurePursuit (0.5 m/s)": RegulatedPurePursuit(goal_tolerance=0.05,
                                                               yaw_tolerance=0.01),
    }
    start = Pose2D(0.0, 0.05, 0.0)
    fig, (ax, ax_err) = plt.subplots(1, 2, figsize=(11, 4.8),
                                     gridspec_kw={"width_ratios": [1.1, 1]})
    ax.plot(path[:, 0], path[:, 1], color="0.6", lw=6, alpha=0.4, label="path")
    for label, tracker in trackers.items():
        poses = run(tracker, path, start, goal_yaw)
        err = cross_track(poses[:, :2], path)
        ax.plot(poses[:, 0], poses[:, 1], lw=1.5, label=label)
        ax_err.plot(np.arange(len(err)) * DT, 100 * err, lw=1.2,
                    label=f"{label.split(' ')[0]}: max {100 * err.max():.1f} cm")
    ax.plot(*start.as_array()[:2], "ko", ms=4)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"{name}: trajectories (start 5 cm off the path)")
    ax.legend(fontsize=8, loc="upper left")
    ax_err.set_xlabel("time (s)")
    ax_err.set_ylabel("cross-track error (cm)")
    ax_err.set_title("distance to the path")
    ax_err.legend(fontsize=8)
    ax_err.grid(alpha=0.3)
    fig.tight_layout()
    out = out_dir / f"trackers_{name.lower().replace(' ', '_').replace('-', '_')}.png"
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


def main(out_dir: Path | None = None) -> list[Path]:
    """Write both figures into ``out_dir`` (default: this script's folder)."""
    target = Path(__file__).resolve().parent if out_dir is None else Path(out_dir)
    target.mkdir(parents=True, exist_ok=True)
    return [
        figure("Right angle", right_angle_path(), math.pi / 2, target),
        figure("S-curve", s_curve_path(), 0.0, target),
    ]


if __name__ == "__main__":
    for written in main(Path(sys.argv[1]) if len(sys.argv) > 1 else None):
        print(written)
