"""ScanMapper under long random runs of scans, each step against the documented update.

A hypothesis state machine feeds a mapper scans (random ranges, some invalid),
with odometry that creeps, turns and jumps metres at a time (so the map grows on
every side), without odometry (the constant-velocity guess), and swaps the mapper
for a copy or a pickle round trip. Each update is checked against the class notes:
the map grows only by whole coarse cells and keeps every cell's value at its world
position; the scan is written, at the pose recorded for it, exactly when it has a
valid return and the pose moved more than ``min_distance`` or turned more than
``min_angle`` since the last write (the first always), and then the finest level is
the previous map (grown) with the scan ray-cast in as
:meth:`OccupancyGrid.integrate_scan` casts it, bit for bit; otherwise the map is
unchanged. Returns with no echo (inf, ``range_max``) or beyond the mapper's
``range_max`` are neither hits nor free space. The trajectory gains one row per
scan, its last row the pose.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, initialize, invariant, rule

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, OccupancyGrid, ScanMapper, ScanMatcher
from stateful_runs import COPIERS, run_machine

RES = 0.1
LEVELS = 2
HIT, MISS, CLAMP = 2.0, -0.5, (-3.0, 4.0)
_COPIERS: tuple[Callable[[ScanMapper], ScanMapper], ...] = COPIERS


def _scan(seed: int, beams: int, invalid: float) -> LaserScan:
    rng = np.random.default_rng(seed)
    ranges = rng.uniform(0.3, 4.0, beams)
    ranges[rng.random(beams) < invalid] = np.nan  # REP 117: no reading
    # "No echo" (REP 117's inf, and range_max itself) and returns beyond the mapper's
    # range_max: neither hits nor free space.
    odd = rng.random(beams)
    ranges[odd < 0.1] = np.inf
    ranges[(odd >= 0.1) & (odd < 0.2)] = 5.0
    ranges[(odd >= 0.2) & (odd < 0.3)] = rng.uniform(3.0, 4.9)
    return LaserScan(
        ranges, angle_min=-math.pi, angle_increment=2 * math.pi / beams,
        range_min=0.1, range_max=5.0,
    )  # fmt: skip


def _grown(old: OccupancyGrid, new: OccupancyGrid) -> OccupancyGrid:
    """``old``'s cells pasted at their world positions into a grid of ``new``'s geometry."""
    assert new.resolution == old.resolution
    dc = (old.origin.x - new.origin.x) / RES
    dr = (old.origin.y - new.origin.y) / RES
    # Only whole coarse cells are added: every cell keeps its world position.
    scale = 2 ** (LEVELS - 1)
    assert abs(dc - round(dc)) < 1e-6 and abs(dr - round(dr)) < 1e-6, (dc, dr)
    c0, r0 = round(dc), round(dr)
    assert c0 % scale == 0 and r0 % scale == 0
    rows, cols = old.shape
    assert r0 >= 0 and r0 + rows <= new.shape[0] and c0 >= 0 and c0 + cols <= new.shape[1]
    values = np.zeros(new.shape, dtype=np.float32)
    values[r0 : r0 + rows, c0 : c0 + cols] = old.logodds
    return OccupancyGrid(values, resolution=RES, origin=new.origin)


class MapperMachine(RuleBasedStateMachine):
    mapper: ScanMapper
    odometry: Pose2D
    min_distance: float
    min_angle: float
    range_max: float | None
    last_write: Pose2D | None
    scans: int

    @initialize(
        min_distance=st.sampled_from([0.0, 0.2, 0.4]),
        min_angle=st.sampled_from([0.0, 0.3, 0.9]),
        start=st.tuples(st.floats(-5.0, 5.0), st.floats(-5.0, 5.0), st.floats(-3.0, 3.0)),
        range_max=st.sampled_from([None, 3.0]),
    )
    def begin(
        self,
        min_distance: float,
        min_angle: float,
        start: tuple[float, float, float],
        range_max: float | None,
    ) -> None:
        self.min_distance, self.min_angle, self.range_max = min_distance, min_angle, range_max
        self.mapper = ScanMapper(
            resolution=RES, hit=HIT, miss=MISS, clamp=CLAMP, min_distance=min_distance,
            min_angle=min_angle, pose=start, range_max=range_max,
            matcher=ScanMatcher(levels=LEVELS, search_distance=0.1, search_angle=0.1),
        )  # fmt: skip
        self.odometry = Pose2D(0.0, 0.0, 0.0)
        self.last_write = None
        self.scans = 0

    @rule(
        seed=st.integers(0, 2**32 - 1),
        beams=st.sampled_from([8, 36, 90]),
        invalid=st.sampled_from([0.0, 0.3, 1.0]),
        move=st.sampled_from(["still", "creep", "turn", "jump", "none"]),
        dx=st.floats(-1.0, 1.0),
        dy=st.floats(-1.0, 1.0),
        dth=st.floats(-1.0, 1.0),
    )
    def scan(
        self, seed: int, beams: int, invalid: float, move: str, dx: float, dy: float, dth: float
    ) -> None:
        scan = _scan(seed, beams, invalid)
        step = {"still": 0.0, "creep": 0.1, "turn": 0.0, "jump": 12.0, "none": 0.0}[move]
        turn = {"turn": 1.5, "creep": 0.1}.get(move, 0.0)
        self.odometry = self.odometry.compose(Pose2D(step * dx, step * dy, turn * dth))
        before = self.mapper.map
        self.mapper.update(scan, None if move == "none" else self.odometry)
        self.scans += 1
        pose = self.mapper.pose
        after = self.mapper.map
        # The returns written: valid (REP 117), closer than the scan's and the mapper's
        # range_max; the others neither hit nor clear (NaN to integrate_scan).
        kept = scan.valid_mask()
        if self.range_max is not None:
            kept &= np.asarray(scan.ranges) < self.range_max
        valid = bool(kept.any())
        if self.scans == 1:
            # The first scan: the map is made around the start (nothing to compare).
            want = OccupancyGrid(np.zeros(after.shape, np.float32), resolution=RES,
                                 origin=after.origin)  # fmt: skip
        else:
            want = _grown(before, after)
        last = self.last_write
        writes = valid and (
            last is None
            or math.hypot(pose.x - last.x, pose.y - last.y) > self.min_distance
            or abs(math.remainder(pose.theta - last.theta, 2 * math.pi)) > self.min_angle
        )
        if writes:
            written = LaserScan(
                np.where(kept, scan.ranges, np.nan), angle_min=scan.angle_min,
                angle_increment=scan.angle_increment, range_min=scan.range_min,
                range_max=scan.range_max,
            )  # fmt: skip
            want.integrate_scan(written, pose, hit=HIT, miss=MISS, clamp=CLAMP)
            self.last_write = pose
        assert after.logodds.tobytes() == want.logodds.tobytes(), (
            writes,
            np.argwhere(after.logodds != want.logodds)[:5],
        )

    @rule(how=st.integers(0, len(_COPIERS) - 1), seed=st.integers(0, 2**32 - 1))
    def swap_for_copy(self, how: int, seed: int) -> None:
        old, self.mapper = self.mapper, _COPIERS[how](self.mapper)
        # The original going on must not reach the copy (the next scan's check would
        # see its writes).
        kept = self.mapper.map.logodds.tobytes()
        old.update(_scan(seed, 36, 0.0), (30.0, -20.0, 1.0))
        assert self.mapper.map.logodds.tobytes() == kept

    @invariant()
    def trajectory_is_one_row_a_scan(self) -> None:
        trajectory = self.mapper.trajectory
        assert trajectory.shape == (self.scans, 3)
        if self.scans:
            assert tuple(trajectory[-1]) == (self.mapper.pose.x, self.mapper.pose.y,
                                             self.mapper.pose.theta)  # fmt: skip


def test_scans_follow_the_documented_update() -> None:
    run_machine(MapperMachine, examples=40, steps=15)


@pytest.mark.slow
def test_scans_follow_the_documented_update_long() -> None:
    run_machine(MapperMachine, examples=200, steps=40)
