"""OmniOdometry under long random sequences of calls, against one batch of every step.

The class notes promise that :meth:`OmniOdometry.update` and
:meth:`OmniOdometry.update_batch` agree bit for bit however the readings are split,
and that a reset is a new start (the steps after it summed apart from its pose). A
hypothesis state machine feeds steps one at a time (the fast path: a float64 array
and a float yaw; and the general one: lists, NumPy scalars, float32, reversed
views), in batches of 0-5, resets (with and without a pose, at the origin and far
from it), makes refused calls (which must change nothing) and swaps the odometry for
a copy or a pickle round trip. After every call the pose must equal, bit for bit, a
fresh odometry from the last reset's pose given every step since in one batch.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, initialize, invariant, rule

from navkit.estimation import OmniOdometry
from navkit.geometry import Pose2D
from navkit.kinematics import OmniDrive
from stateful_runs import COPIERS, run_machine

_COPIERS: tuple[Callable[[OmniOdometry], OmniOdometry], ...] = COPIERS
_INC = st.floats(-3.0, 3.0, allow_nan=False)
_YAW = st.floats(-10.0, 10.0, allow_nan=False)
_POSE = st.tuples(
    st.sampled_from([0.0, 1.5, -3.25, 5.0e6]),
    st.sampled_from([0.0, -2.0, 4.4e6]),
    st.floats(-3.0, 3.0),
)


class OmniMachine(RuleBasedStateMachine):
    drive: OmniDrive
    odometry: OmniOdometry
    start_pose: Pose2D | None  # None: the constructor's default
    increments: list[list[float]]
    yaws: list[float]

    @initialize(
        wheels=st.sampled_from([3, 4, 5]),
        radius=st.sampled_from([0.03, 0.05]),
        pose=st.none() | _POSE,
    )
    def start(self, wheels: int, radius: float, pose: tuple[float, float, float] | None) -> None:
        if wheels == 3:
            self.drive = OmniDrive.three_wheel(wheel_radius=radius, base_radius=0.2)
        else:
            angles = np.linspace(0.3, 0.3 + 2 * math.pi, wheels, endpoint=False)
            self.drive = OmniDrive(angles, wheel_radius=radius, base_radius=0.25)
        self.odometry = OmniOdometry(self.drive, pose=pose)
        self.start_pose = None if pose is None else Pose2D(*pose)
        self.increments = []
        self.yaws = []

    def _n(self) -> int:
        return self.drive.n_wheels

    @rule(data=st.data(), yaw=_YAW, kind=st.sampled_from(["fast", "list", "numpy", "reversed"]))
    def update(self, data: st.DataObject, yaw: float, kind: str) -> None:
        inc = data.draw(st.lists(_INC, min_size=self._n(), max_size=self._n()))
        arg: Any
        yaw_arg: Any = yaw
        if kind == "fast":
            arg = np.array(inc)
        elif kind == "list":
            arg = list(inc)
        elif kind == "numpy":
            arg = np.array(inc)
            yaw_arg = np.float64(yaw)
        else:
            arg = np.array(inc[::-1])[::-1]  # a view with a negative stride
        pose = self.odometry.update(arg, yaw_arg)
        assert pose == self.odometry.pose
        self.increments.append(inc)
        self.yaws.append(yaw)

    @rule(data=st.data(), k=st.integers(0, 5))
    def update_batch(self, data: st.DataObject, k: int) -> None:
        rows = data.draw(
            st.lists(st.lists(_INC, min_size=self._n(), max_size=self._n()), min_size=k, max_size=k)
        )
        yaws = data.draw(st.lists(_YAW, min_size=k, max_size=k))
        before = self.odometry.pose
        out = self.odometry.update_batch(np.array(rows).reshape(k, self._n()), yaws)
        assert out.shape == (k + 1, 3)
        np.testing.assert_array_equal(out[0], before.as_array())
        np.testing.assert_array_equal(out[-1], self.odometry.pose.as_array())
        self.increments.extend(rows)
        self.yaws.extend(yaws)

    @rule(pose=st.none() | _POSE)
    def reset(self, pose: tuple[float, float, float] | None) -> None:
        before = self.odometry.pose
        self.odometry.reset(pose)
        if pose is None:
            assert self.odometry.pose == before  # nothing to forget
            return
        self.start_pose = Pose2D(*pose)
        self.increments = []
        self.yaws = []

    @rule(kind=st.sampled_from(["nan increment", "inf yaw", "shape", "bool yaw"]))
    def refused(self, kind: str) -> None:
        before = self.odometry.pose
        inc: Any = np.zeros(self._n())
        yaw: Any = 0.0
        if kind == "nan increment":
            inc[0] = math.nan
        elif kind == "inf yaw":
            yaw = math.inf
        elif kind == "shape":
            inc = np.zeros(self._n() + 1)
        else:
            yaw = True
        with pytest.raises((ValueError, TypeError)):
            self.odometry.update(inc, yaw)
        assert self.odometry.pose == before

    @rule(how=st.integers(0, len(_COPIERS) - 1))
    def swap_for_copy(self, how: int) -> None:
        old, self.odometry = self.odometry, _COPIERS[how](self.odometry)
        # The original going on must not reach the copy (checked by the invariant).
        old.update(np.ones(self._n()), 1.0)
        old.reset((1.0, 2.0, 3.0))

    @invariant()
    def equals_one_batch_of_every_step(self) -> None:
        fresh = OmniOdometry(self.drive, pose=self.start_pose)
        n = len(self.yaws)
        out = fresh.update_batch(np.array(self.increments).reshape(n, self._n()), self.yaws)
        assert self.odometry.pose.as_array().tobytes() == out[-1].tobytes(), (
            self.odometry.pose,
            out[-1],
        )


def test_split_readings_equal_one_batch() -> None:
    run_machine(OmniMachine, examples=60, steps=25)


@pytest.mark.slow
def test_split_readings_equal_one_batch_long() -> None:
    run_machine(OmniMachine, examples=400, steps=50)
