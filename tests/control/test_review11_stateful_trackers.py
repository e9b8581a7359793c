"""Path trackers under long random sequences of paths, steps, refused calls and copies.

A hypothesis state machine drives a simulated robot with the commands of
:class:`FollowTheCarrot`, :class:`OnOffTracker` or :class:`RegulatedPurePursuit`
(differential or omnidirectional), with random control periods, localisation
jumps, new paths (duplicates, single points, goal headings) at any time, refused
steps (bad ``dt`` or pose) and swaps for a copy or a pickle round trip. After
every step: :attr:`progress` never decreases and stays on the path, commands
respect the tracker's limits (``vy = 0`` for a differential drive), a ``done``
tracker commands zero until the next path, a refused step changes nothing (the
tracker then commands what a copy taken before it commands), and a copy commands
exactly what its original does.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, initialize, invariant, rule

from navkit.control import FollowTheCarrot, OnOffTracker, RegulatedPurePursuit
from navkit.geometry import Pose2D, Twist2D
from stateful_runs import COPIERS, run_machine

Tracker = FollowTheCarrot | OnOffTracker | RegulatedPurePursuit
_COPIERS: tuple[Callable[[Tracker], Tracker], ...] = COPIERS


def _make(kind: str, drive: str) -> tuple[Tracker, float, float]:
    """A tracker, its speed limit (m/s) and its turn-rate limit (rad/s)."""
    if kind == "carrot":
        carrot = FollowTheCarrot(max_speed=0.3, max_omega=1.2, drive=drive)  # type: ignore[arg-type]
        return carrot, 0.3, 1.2
    if kind == "on-off":
        on_off = OnOffTracker(max_speed=0.25, rotate_omega=0.8, drive=drive)  # type: ignore[arg-type]
        return on_off, 0.25, 0.8
    rpp = RegulatedPurePursuit(max_speed=0.4, max_omega=1.0, rotate_omega=1.5, drive=drive)  # type: ignore[arg-type]
    return rpp, 0.4, 1.5


class TrackerMachine(RuleBasedStateMachine):
    rng: np.random.Generator
    tracker: Tracker
    speed_limit: float
    turn_limit: float
    pose: Pose2D
    progress: float
    length: float
    has_path: bool

    @initialize(
        kind=st.sampled_from(["carrot", "on-off", "rpp"]),
        drive=st.sampled_from(["diff", "omni"]),
        seed=st.integers(0, 2**32 - 1),
    )
    def start(self, kind: str, drive: str, seed: int) -> None:
        self.rng = np.random.default_rng(seed)
        self.tracker, self.speed_limit, self.turn_limit = _make(kind, drive)
        self.pose = Pose2D(0.0, 0.0, 0.0)
        self.progress = 0.0
        self.length = 0.0
        self.has_path = False
        with pytest.raises(RuntimeError):
            self.tracker.step(self.pose, 0.1)

    @rule(
        points=st.integers(1, 6),
        duplicate=st.booleans(),
        heading=st.none() | st.floats(-4.0, 4.0),
        from_robot=st.booleans(),
    )
    def set_path(
        self, points: int, duplicate: bool, heading: float | None, from_robot: bool
    ) -> None:
        xy = np.cumsum(self.rng.uniform(-1.0, 1.0, size=(points, 2)), axis=0)
        if from_robot:
            xy += [self.pose.x, self.pose.y]
        if duplicate:
            xy = np.repeat(xy, 2, axis=0)
        self.tracker.set_path(xy, goal_yaw=heading)
        # FollowTheCarrot on a differential drive starts by turning in place.
        assert self.tracker.phase in ("track", "rotate") and not self.tracker.done
        assert self.tracker.progress == 0.0
        self.progress = 0.0
        self.length = float(np.sum(np.hypot(*np.diff(xy, axis=0).T)))
        self.has_path = True

    def _check(self, twist: Twist2D, was_done: bool) -> None:
        if was_done:
            assert twist == Twist2D(0.0, 0.0, 0.0)
            assert self.tracker.done
        assert all(math.isfinite(v) for v in (twist.vx, twist.vy, twist.omega))
        assert math.hypot(twist.vx, twist.vy) <= self.speed_limit * (1.0 + 1e-9)
        assert abs(twist.omega) <= self.turn_limit * (1.0 + 1e-9)
        if self.tracker.drive == "diff":
            assert twist.vy == 0.0
        assert self.tracker.progress >= self.progress
        assert self.tracker.progress <= self.length * (1.0 + 1e-9) + 1e-9
        self.progress = self.tracker.progress

    @rule(dt=st.sampled_from([0.01, 0.05, 0.1, 0.3]), steps=st.integers(1, 20))
    def drive(self, dt: float, steps: int) -> None:
        self._drive(dt, steps)

    @rule()
    def drive_to_the_goal(self) -> None:
        self._drive(0.1, 600, until_done=True)

    def _drive(self, dt: float, steps: int, until_done: bool = False) -> None:
        if not self.has_path:
            return
        left = steps
        while left > 0:
            left -= 1
            if until_done and self.tracker.done:
                left, until_done = 3, False  # a few more steps: the commands stay zero
            was_done = self.tracker.done
            twist = self.tracker.step(self.pose, dt)
            self._check(twist, was_done)
            # The robot follows the command exactly (body frame, then world frame).
            c, s = math.cos(self.pose.theta), math.sin(self.pose.theta)
            self.pose = Pose2D(
                self.pose.x + (c * twist.vx - s * twist.vy) * dt,
                self.pose.y + (s * twist.vx + c * twist.vy) * dt,
                self.pose.theta + twist.omega * dt,
            )

    @rule(dx=st.floats(-1.0, 1.0), dy=st.floats(-1.0, 1.0), dth=st.floats(-3.0, 3.0))
    def localisation_jump(self, dx: float, dy: float, dth: float) -> None:
        self.pose = Pose2D(self.pose.x + dx, self.pose.y + dy, self.pose.theta + dth)

    @rule(bad=st.sampled_from(["dt 0", "dt < 0", "dt nan", "dt subnormal", "pose nan", "far"]))
    def refused_step(self, bad: str) -> None:
        if not self.has_path:
            return
        before = copy.deepcopy(self.tracker)
        state = (self.tracker.phase, self.tracker.progress, self.tracker.target_xy)
        dt: Any = {"dt 0": 0.0, "dt < 0": -0.1, "dt nan": math.nan, "dt subnormal": 1e-310}.get(
            bad, 0.1
        )
        pose: Any = {"pose nan": (math.nan, 0.0, 0.0), "far": (2e9, 0.0, 0.0)}.get(bad, self.pose)
        with pytest.raises((ValueError, TypeError)):
            self.tracker.step(pose, dt)
        assert (self.tracker.phase, self.tracker.progress, self.tracker.target_xy) == state
        assert self.tracker.step(self.pose, 0.05) == before.step(self.pose, 0.05)
        self._check_pair(before)

    def _check_pair(self, other: Tracker) -> None:
        assert other.phase == self.tracker.phase
        assert other.progress == self.tracker.progress
        assert other.target_xy == self.tracker.target_xy
        self.progress = self.tracker.progress

    @rule(how=st.integers(0, len(_COPIERS) - 1))
    def swap_for_copy(self, how: int) -> None:
        twin = _COPIERS[how](self.tracker)
        if self.has_path:
            assert twin.step(self.pose, 0.05) == self.tracker.step(self.pose, 0.05)
            self._check_pair(twin)
            path = twin.path_xy
            assert path is not None
            kept = path.copy()
            # The original changing must not reach the copy.
            self.tracker.set_path([[50.0, 50.0], [51.0, 50.0]])
            self.tracker.step(self.pose, 0.05)
            after = twin.path_xy
            assert after is not None and np.array_equal(after, kept)
        self.tracker = twin

    @invariant()
    def progress_is_kept(self) -> None:
        assert self.tracker.progress >= self.progress


def test_trackers_under_random_sequences() -> None:
    run_machine(TrackerMachine, examples=30, steps=15)


@pytest.mark.slow
def test_trackers_under_random_sequences_long() -> None:
    run_machine(TrackerMachine, examples=400, steps=40)
