"""DiffOdometry under long random sequences of readings, checked against a plain model.

A hypothesis state machine drives two wheel counters by random amounts (up to
a few turns, or nearly half the counter range on narrow counters), reads them as
the hardware shows them (modulo ``2**encoder_bits``, signed or unsigned), and
feeds them one at a time (:meth:`DiffOdometry.update`), in batches of 0-6 (lists,
int64, uint64, object arrays), with resets, refused readings (which must change
nothing) and swaps for a copy or a pickle round trip. After every step the pose
equals a pure-Python integration of the documented model: signed tick deltas
modulo the counter width, per-wheel metres per tick, then the ``"arc"``,
``"midpoint"`` or ``"first_order"`` step, the heading wrapped to (-π, π].
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, initialize, invariant, rule

from navkit.estimation import DiffOdometry
from navkit.kinematics import DiffDrive
from stateful_runs import COPIERS, run_machine

TRACK = 0.4
_COPIERS: tuple[Callable[[DiffOdometry], DiffOdometry], ...] = COPIERS


def _wrap(angle: float) -> float:
    w = math.remainder(angle, 2.0 * math.pi)
    return math.pi if w == -math.pi else w


class OdometryMachine(RuleBasedStateMachine):
    rng: np.random.Generator
    odometry: DiffOdometry
    method: str
    ticks_per_rev: float
    radii: tuple[float, float]
    modulus: int
    lowest: int
    highest: int
    largest_step: int
    counts: list[int]  # the true, unwrapped counts
    last: tuple[int, int] | None
    pose: list[float]

    @initialize(
        bits=st.sampled_from([None, 2, 3, 8, 16, 32, 63, 64]),
        method=st.sampled_from(["arc", "midpoint", "first_order"]),
        ticks_per_rev=st.sampled_from([1.0, 4.0, 1000.0, 4096.0]),
        left=st.sampled_from([0.05, 0.1]),
        right=st.sampled_from([0.05, 0.1]),
        seed=st.integers(0, 2**32 - 1),
    )
    def start(
        self, bits: int | None, method: str, ticks_per_rev: float, left: float, right: float,
        seed: int,
    ) -> None:
        self.rng = np.random.default_rng(seed)
        drive = DiffDrive(track=TRACK, left_radius=left, right_radius=right)
        self.odometry = DiffOdometry(
            drive, ticks_per_rev=ticks_per_rev, bits=bits, method=method  # type: ignore[arg-type]
        )
        self.method, self.ticks_per_rev, self.radii = method, ticks_per_rev, (left, right)
        width = 64 if bits is None else bits
        self.modulus = 1 << width
        self.lowest, self.highest = -(1 << (width - 1)), (1 << width) - 1
        # Steps below half the counter range, so that the wrapped delta is the true one.
        self.largest_step = max(1, min((1 << (width - 1)) - 1, 3 * int(ticks_per_rev)))
        self.counts = [0, 0]
        self.last = None
        self.pose = [0.0, 0.0, 0.0]

    def _reading(self, count: int) -> int:
        shown = count % self.modulus
        if shown >= self.modulus // 2 and self.rng.random() < 0.5:
            shown -= self.modulus  # the signed form of the same counter value
        return shown

    def _advance(self) -> tuple[int, int]:
        for i in range(2):
            self.counts[i] += int(self.rng.integers(-self.largest_step, self.largest_step + 1))
        return self._reading(self.counts[0]), self._reading(self.counts[1])

    def _model_step(self, left: int, right: int) -> None:
        if self.last is None:  # the first reading only latches the counters
            self.last = (left, right)
            return
        deltas = []
        for now, before in zip((left, right), self.last, strict=True):
            d = (now - before) % self.modulus
            deltas.append(d - self.modulus if d >= self.modulus // 2 else d)
        self.last = (left, right)
        d_left, d_right = (
            2.0 * math.pi * r / self.ticks_per_rev * d
            for r, d in zip(self.radii, deltas, strict=True)
        )
        dc = (d_left + d_right) / 2.0
        dth = (d_right - d_left) / TRACK
        if self.method == "first_order":
            dx, dy = dc, 0.0
        elif self.method == "midpoint":
            dx, dy = dc * math.cos(dth / 2.0), dc * math.sin(dth / 2.0)
        elif abs(dth) < 1e-9:
            dx, dy = dc, dc * dth / 2.0
        else:
            dx, dy = dc * math.sin(dth) / dth, dc * (1.0 - math.cos(dth)) / dth
        x, y, th = self.pose
        c, s = math.cos(th), math.sin(th)
        self.pose = [x + c * dx - s * dy, y + s * dx + c * dy, _wrap(th + dth)]

    @rule()
    def update(self) -> None:
        left, right = self._advance()
        pose = self.odometry.update(left, right)
        self._model_step(left, right)
        assert pose == self.odometry.pose

    @rule(k=st.integers(0, 6), kind=st.sampled_from(["list", "int64", "uint64", "object"]))
    def update_batch(self, k: int, kind: str) -> None:
        readings = [self._advance() for _ in range(k)]
        lefts: Any = [a for a, _ in readings]
        rights: Any = [b for _, b in readings]
        values = lefts + rights
        if kind == "int64" and all(-(2**63) <= v < 2**63 for v in values):
            lefts, rights = np.array(lefts, dtype=np.int64), np.array(rights, dtype=np.int64)
        elif kind == "uint64" and all(0 <= v < 2**64 for v in values):
            lefts, rights = np.array(lefts, dtype=np.uint64), np.array(rights, dtype=np.uint64)
        elif kind == "object":
            lefts, rights = np.array(lefts, dtype=object), np.array(rights, dtype=object)
        out = self.odometry.update_batch(lefts, rights)
        assert out.shape == (k, 3)
        for i, (a, b) in enumerate(readings):
            self._model_step(a, b)
            scale = 1.0 + abs(self.pose[0]) + abs(self.pose[1])
            np.testing.assert_allclose(out[i, :2], self.pose[:2], rtol=0.0, atol=1e-9 * scale)
            assert abs(_wrap(out[i, 2] - self.pose[2])) <= 1e-9

    @rule(new_pose=st.booleans())
    def reset(self, new_pose: bool) -> None:
        pose = (1.0, -2.0, 3.0) if new_pose else None
        self.odometry.reset(pose)
        self.last = None
        if pose is not None:
            self.pose = list(pose)

    @rule(kind=st.sampled_from(["above", "below", "float", "bool", "lengths", "list"]))
    def refused(self, kind: str) -> None:
        calls: dict[str, Callable[[], Any]] = {
            "above": lambda: self.odometry.update(self.highest + 1, 0),
            "below": lambda: self.odometry.update_batch([0, self.lowest - 1], [0, 0]),
            "float": lambda: self.odometry.update(1.5, 0),  # type: ignore[arg-type]
            "bool": lambda: self.odometry.update(True, 0),
            "lengths": lambda: self.odometry.update_batch([0, 1], [0]),
            "list": lambda: self.odometry.update([0], 0),  # type: ignore[arg-type]
        }
        with pytest.raises((TypeError, ValueError)):
            calls[kind]()

    @rule(how=st.integers(0, len(_COPIERS) - 1))
    def swap_for_copy(self, how: int) -> None:
        old, self.odometry = self.odometry, _COPIERS[how](self.odometry)
        # The original moving on must not reach the copy (checked by the invariant).
        old.reset((5.0, 5.0, 0.0))
        old.update(0, 0)
        old.update(1, 3)

    @invariant()
    def pose_is_the_model(self) -> None:
        pose = self.odometry.pose
        scale = 1.0 + abs(self.pose[0]) + abs(self.pose[1])
        assert abs(pose.x - self.pose[0]) <= 1e-9 * scale
        assert abs(pose.y - self.pose[1]) <= 1e-9 * scale
        assert abs(_wrap(pose.theta - self.pose[2])) <= 1e-9
        assert -math.pi < pose.theta <= math.pi


def test_reading_sequences_match_the_model() -> None:
    run_machine(OdometryMachine, examples=30, steps=20)


@pytest.mark.slow
def test_reading_sequences_match_the_model_long() -> None:
    run_machine(OdometryMachine, examples=400, steps=40)
