"""A tracker given a new path every cycle of a replanning loop (review 34, long runs).

The control guide says one tracker follows successive replans through
``set_path``, and that ``set_path`` makes it a new tracker, its memory of
previous commands cleared. ``RegulatedPurePursuit`` bases its lookahead and its
angular acceleration limit on the previous command when ``step`` gets no
``velocity=``: at each new path it took the robot to be at rest. The guide now
says so, with the remedy (pass ``velocity=``) and the figures below.
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import numpy as np

from navkit.control import RegulatedPurePursuit

ROOT = Path(__file__).resolve().parents[2]
DT = 0.05
BEHIND = [[0.0, 0.0], [-3.0, 0.0]]  # the path leaves behind the robot: it turns in place


def _guide() -> str:
    return " ".join((ROOT / "docs/guides/control.md").read_text(encoding="utf-8").split())


def _turning(*, replan_every: int, measured: bool, steps: int = 40) -> list[float]:
    tracker = RegulatedPurePursuit()
    tracker.set_path(BEHIND)
    theta, omega, out = 0.0, 0.0, []
    for k in range(steps):
        if replan_every and k and k % replan_every == 0:
            tracker.set_path(BEHIND)  # the same plan again, as a replanner gives it
        kwargs = {"velocity": (0.0, 0.0, omega)} if measured else {}
        omega = tracker.step((0.0, 0.0, theta), DT, **kwargs).omega
        out.append(omega)
        theta += omega * DT
    return out


def test_a_new_path_without_velocity_restarts_the_turn_from_rest() -> None:
    limit = 3.2 * DT  # Nav2's max_angular_accel (the default), rad/s², times the period
    alone = _turning(replan_every=0, measured=False)
    replanned = _turning(replan_every=10, measured=False)
    assert alone[:10] == replanned[:10]
    before, after = replanned[9], replanned[10]
    # As the guide says: 1.6 rad/s, then 0.16 at the new path, nine times the limit.
    assert round(before, 9) == 1.6 and round(after, 9) == round(limit, 9)
    assert round((before - after) / limit) == 9
    assert "1.6 rad/s was commanded 0.16 rad/s at each new path" in _guide()
    assert "a drop nine times what `max_angular_accel` allows in a step" in _guide()
    # Uninterrupted, the turn never drops so.
    assert max(abs(a - b) for a, b in itertools.pairwise(alone[:13])) <= limit + 1e-12


def test_the_measured_velocity_carries_the_turn_across_new_paths() -> None:
    alone = _turning(replan_every=0, measured=True)
    replanned = _turning(replan_every=10, measured=True)
    assert replanned == alone
    # While it turns in place, the same turn as from its own previous commands.
    assert alone[:30] == _turning(replan_every=0, measured=False)[:30]


def test_a_new_path_without_velocity_looks_ahead_the_minimum_for_a_step() -> None:
    s = np.linspace(0.0, 10.0, 201)
    route = np.column_stack([s, 2.0 * np.sin(s / 3.0)])
    tracker = RegulatedPurePursuit()
    tracker.set_path(route)
    pose = (2.0, float(2.0 * np.sin(2.0 / 3.0)), math.atan(2.0 / 3.0 * math.cos(2.0 / 3.0)))
    for _ in range(5):
        tracker.step(pose, DT)
    moving = math.dist(tracker.target_xy or (0.0, 0.0), pose[:2])
    tracker.set_path(route[40:])  # a plan from about where the robot is
    tracker.step(pose, DT)
    restarted = math.dist(tracker.target_xy or (0.0, 0.0), pose[:2])
    assert math.isclose(restarted, 0.3, rel_tol=1e-6)  # Nav2's min_lookahead_dist
    assert moving > 0.7  # max_speed × lookahead_time, 0.5 × 1.5 m
    assert "looked ahead only `min_lookahead` for a step" in _guide()
