"""PotentialFieldController under long random runs of steps, resets, refusals and copies.

The controller keeps a previous velocity, a PID integrator and last error, and a
stall anchor and timer between steps. A hypothesis state machine steps it with
random poses (held, crept, jumped), targets, periods, obstacles (points with
invalid rows, scans, none) and measured velocities (also above ``max_speed``), for
both drives; resets it; makes refused calls; and swaps it for a copy or a pickle
round trip. After every call: each command keeps within ``max_speed`` and
``max_omega`` and, from the previous command (no measured velocity), changes the
world velocity by at most ``max(max_accel, max_decel) × dt``; the stall timer
follows the class notes (time within ``stall_radius`` of one spot while farther
than ``goal_tolerance`` from the goal); and the controller equals, bit for bit, a
fresh one given the calls taken since the last reset (so a reset forgets all,
and a refused call or a copy's later steps change nothing).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, initialize, invariant, rule

from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D, Twist2D
from navkit.mapping import LaserScan
from stateful_runs import COPIERS, run_machine

_COPIERS: tuple[Callable[[Any], Any], ...] = COPIERS
OPTIONS = {"max_speed": 0.5, "max_accel": 1.0, "max_decel": 2.0, "max_omega": 2.0,
           "stall_radius": 0.05, "stall_timeout": 0.5, "goal_tolerance": 0.05}  # fmt: skip


def _state(ctl: PotentialFieldController) -> tuple[Any, ...]:
    return (
        ctl.previous_velocity.tobytes(),
        ctl.stall_time,
        ctl.stalled,
        ctl._integral,
        ctl._last_error,
        None if ctl._anchor is None else ctl._anchor.tobytes(),
    )


class ControllerMachine(RuleBasedStateMachine):
    drive: str
    ctl: PotentialFieldController
    calls: list[tuple[Any, ...]]  # the step arguments since the last reset
    pose: Pose2D
    still_since: tuple[float, float] | None  # the model's stall anchor
    still_for: float

    @initialize(drive=st.sampled_from(["omni", "diff"]))
    def start(self, drive: str) -> None:
        self.drive = drive
        self.ctl = PotentialFieldController(drive=drive, **OPTIONS)  # type: ignore[arg-type]
        self.calls = []
        self.pose = Pose2D(0.0, 0.0, 0.0)
        self.still_since = None
        self.still_for = 0.0

    @rule(
        move=st.sampled_from(["hold", "creep", "jump"]),
        d=st.tuples(st.floats(-1, 1), st.floats(-1, 1), st.floats(-3, 3)),
        goal=st.tuples(st.floats(-3, 3), st.floats(-3, 3), st.floats(-3, 3)),
        near_goal=st.booleans(),
        dt=st.sampled_from([1e-3, 0.05, 0.1, 0.3]),
        obstacles=st.sampled_from(["none", "points", "scan"]),
        measured=st.none()
        | st.tuples(st.floats(-0.8, 0.8), st.floats(-0.8, 0.8), st.floats(-3, 3)),
    )
    def step(
        self,
        move: str,
        d: tuple[float, float, float],
        goal: tuple[float, float, float],
        near_goal: bool,
        dt: float,
        obstacles: str,
        measured: tuple[float, float, float] | None,
    ) -> None:
        target = goal
        scale = {"hold": 0.0, "creep": 0.02, "jump": 1.0}[move]
        p = self.pose
        self.pose = Pose2D(p.x + scale * d[0], p.y + scale * d[1], p.theta + (scale > 0) * d[2])
        if near_goal:  # the goal within goal_tolerance: no stall there
            target = (self.pose.x + 0.01, self.pose.y - 0.01, target[2])
        obs: Any = None
        if obstacles == "points":
            obs = np.array([[self.pose.x + 0.3, self.pose.y], [math.nan, 1.0], [1.0, -1.0]])
        elif obstacles == "scan":
            obs = LaserScan(
                [0.4, math.inf, 1.0, math.nan], angle_min=-1.0, angle_increment=0.7,
                range_min=0.05, range_max=5.0,
            )  # fmt: skip
        before = self.ctl.previous_velocity
        cmd = self.ctl.step(self.pose, target, dt, obstacles=obs, velocity=measured)
        self.calls.append((self.pose, target, dt, obs, measured))
        speed = math.hypot(cmd.vx, cmd.vy)
        assert speed <= OPTIONS["max_speed"] * (1 + 1e-12)
        assert abs(cmd.omega) <= OPTIONS["max_omega"]
        after = self.ctl.previous_velocity
        if measured is None:
            limit = max(OPTIONS["max_accel"], OPTIONS["max_decel"]) * dt
            change = float(np.hypot(*(after - before)))
            if self.drive == "omni":
                assert change <= limit * (1 + 1e-9) + 1e-15, (change, limit)
            else:  # the forward speed, along whatever heading
                gap = abs(float(np.hypot(*after)) - float(np.hypot(*before)))
                assert gap <= limit * (1 + 1e-9) + 1e-15, (gap, limit)
        self._stall_model(target, dt)

    def _stall_model(self, target: tuple[float, float, float], dt: float) -> None:
        x, y = self.pose.x, self.pose.y
        if math.hypot(target[0] - x, target[1] - y) <= OPTIONS["goal_tolerance"]:
            self.still_since, self.still_for = None, 0.0
        elif (
            self.still_since is None
            or math.hypot(x - self.still_since[0], y - self.still_since[1])
            > OPTIONS["stall_radius"]
        ):
            self.still_since, self.still_for = (x, y), 0.0
        else:
            self.still_for += dt
        assert math.isclose(self.ctl.stall_time, self.still_for, rel_tol=1e-12, abs_tol=1e-15)
        if self.still_for >= OPTIONS["stall_timeout"] * (1 + 1e-9):
            assert self.ctl.stalled
        if self.still_for <= OPTIONS["stall_timeout"] * (1 - 1e-9):
            assert not self.ctl.stalled

    @rule()
    def reset(self) -> None:
        self.ctl.reset()
        self.calls = []
        self.still_since, self.still_for = None, 0.0
        assert not self.ctl.stalled and self.ctl.stall_time == 0.0

    @rule(
        kind=st.sampled_from(["nan pose", "dt 0", "far target", "huge velocity", "bad obstacles"])
    )
    def refused(self, kind: str) -> None:
        before = _state(self.ctl)
        args: dict[str, Any] = {"pose": self.pose, "target_pose": (1.0, 1.0, 0.0), "dt": 0.1}
        if kind == "nan pose":
            args["pose"] = (math.nan, 0.0, 0.0)
        elif kind == "dt 0":
            args["dt"] = 0.0
        elif kind == "far target":
            args["target_pose"] = (2e9, 0.0, 0.0)
        elif kind == "huge velocity":
            # |vx| + |vy| of the world frame is at least the speed, 2.4e308 m/s: refused at
            # every heading. (1e308 each is not: see the test below.)
            args["velocity"] = Twist2D(1.7e308, 1.7e308, 0.0)
        else:
            args["obstacles"] = [[1.0, 2.0, 3.0]]
        with pytest.raises((ValueError, TypeError)):
            self.ctl.step(**args)
        assert _state(self.ctl) == before

    @rule(how=st.integers(0, len(_COPIERS) - 1))
    def swap_for_copy(self, how: int) -> None:
        old, self.ctl = self.ctl, _COPIERS[how](self.ctl)
        assert _state(self.ctl) == _state(old)
        # The original going on must not reach the copy (checked by the invariant).
        old.step((5.0, 5.0, 1.0), (0.0, 0.0, 0.0), 0.2, velocity=(0.3, 0.1, 0.5))

    @invariant()
    def equals_a_fresh_controller_given_the_calls_since_reset(self) -> None:
        fresh = PotentialFieldController(drive=self.drive, **OPTIONS)  # type: ignore[arg-type]
        for pose, target, dt, obs, measured in self.calls:
            fresh.step(pose, target, dt, obstacles=obs, velocity=measured)
        assert _state(self.ctl) == _state(fresh)


def test_controller_runs_follow_the_model() -> None:
    run_machine(ControllerMachine, examples=60, steps=25)


@pytest.mark.slow
def test_controller_runs_follow_the_model_long() -> None:
    run_machine(ControllerMachine, examples=300, steps=60)


@pytest.mark.parametrize("drive", ["omni", "diff"])
def test_a_measured_velocity_beyond_1e154_neither_warns_nor_raises(drive: str) -> None:
    # Finite world components at heading 1 rad (the check refuses only their overflow):
    # the command is max_speed at most, as from any measured velocity above it, but
    # NumPy warned "overflow encountered in dot" (an error under -W error, the step lost).
    ctl = PotentialFieldController(drive=drive)  # type: ignore[arg-type]
    cmd = ctl.step((0.0, 0.0, 1.0), (1.0, 1.0, 0.0), 0.1, velocity=Twist2D(1e200, 0.0, 0.0))
    # Decelerating from 1e200 m/s by max_decel dt leaves far more than max_speed.
    assert math.hypot(cmd.vx, cmd.vy) == pytest.approx(ctl.max_speed, rel=1e-12)
