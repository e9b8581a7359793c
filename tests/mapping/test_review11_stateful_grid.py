"""OccupancyGrid under long random sequences of scans, copies and refused calls.

A hypothesis state machine integrates random scans (beams with no return, NaN,
too close, ending inside and outside the map, the sensor inside or outside it)
with varying ``hit``, ``miss`` and ``clamp`` into a grid whose log-odds start
anywhere (beyond the clamp bounds too), swaps the grid for a copy or a pickle
round trip, and makes invalid calls. Which cells a scan reaches is geometry
alone, so it is read from the same scan cast into a zero grid; the change of
every cell is then checked against the documented update rule: a hit adds
``hit`` but stops at ``clamp[1]`` and leaves a cell already at or above it alone,
a miss likewise towards ``clamp[0]``, and every other cell keeps its value. The
returned count is the number of cells reached, whatever their values. Copies are
independent, the public log-odds stay read-only float32.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, initialize, invariant, rule

from navkit.mapping import LaserScan, OccupancyGrid
from stateful_runs import COPIERS, run_machine

RES = 0.25
Array = np.ndarray[Any, np.dtype[np.float64]]
Mask = np.ndarray[Any, np.dtype[np.bool_]]
_COPIERS: tuple[Callable[[OccupancyGrid], OccupancyGrid], ...] = (OccupancyGrid.copy, *COPIERS)
_CLAMP = (math.log(0.12 / 0.88), math.log(0.97 / 0.03))
_DEFAULTS = (math.log(0.7 / 0.3), math.log(0.4 / 0.6), _CLAMP)
# (hit, miss, clamp); None: the defaults, not passed.
_PARAMETERS: list[tuple[float, float, tuple[float, float]] | None] = [
    None,
    (2.0, -1.0, (-3.0, 3.0)),
    (0.0, -0.4, (-2.0, 3.5)),
    (0.85, 0.0, (-2.0, 3.5)),
    (5.0, -5.0, (-1.0, 1.0)),
    (1.0, -1.0, (0.5, 4.0)),  # both bounds positive
    (1.0, -1.0, (-4.0, -0.5)),  # both bounds negative
]


def _updated(
    before: Array, hit_cells: Mask, miss_cells: Mask, hit: float, miss: float,
    low: float, high: float,
) -> Array:
    """The documented per-cell rule (float32 increments, as the grid stores float32)."""
    out = before.copy()
    v = before[hit_cells]
    out[hit_cells] = np.where(v >= high, v, np.minimum(v + float(np.float32(hit)), high))
    v = before[miss_cells]
    out[miss_cells] = np.where(v <= low, v, np.maximum(v + float(np.float32(miss)), low))
    return out


class GridMachine(RuleBasedStateMachine):
    rng: np.random.Generator
    grid: OccupancyGrid
    model: Array

    @initialize(
        rows=st.integers(1, 12),
        cols=st.integers(1, 12),
        seed=st.integers(0, 2**32 - 1),
        yaw=st.sampled_from([0.0, 0.3, -2.0]),
    )
    def start(self, rows: int, cols: int, seed: int, yaw: float) -> None:
        self.rng = np.random.default_rng(seed)
        spread = float(self.rng.choice([0.0, 0.0, 3.0, 10.0]))  # 10: beyond the clamp
        self.grid = OccupancyGrid(
            spread * self.rng.normal(size=(rows, cols)), resolution=RES, origin=(0.3, -0.2, yaw)
        )
        self.model = self.grid.logodds.astype(np.float64)

    def _scan(self) -> LaserScan:
        n = int(self.rng.integers(1, 12))
        ranges = self.rng.uniform(0.0, 5.0, size=n)
        kind = self.rng.random(n)
        ranges[kind < 0.1] = np.inf  # no return: clears up to range_max
        ranges[(kind >= 0.1) & (kind < 0.15)] = np.nan  # skipped
        ranges[(kind >= 0.15) & (kind < 0.2)] = 0.01  # below range_min: skipped
        return LaserScan(
            ranges,
            angle_min=float(self.rng.uniform(-math.pi, math.pi)),
            angle_increment=float(self.rng.uniform(0.01, 0.25)),
            range_min=0.05,
            range_max=float(self.rng.choice([3.0, 10.0])),
        )

    @rule(which=st.integers(0, len(_PARAMETERS) - 1), exact=st.booleans())
    def integrate_scan(self, which: int, exact: bool) -> None:
        scan = self._scan()
        rows, cols = self.grid.shape
        pose = (
            float(self.rng.uniform(-0.5, cols * RES + 0.5)),
            float(self.rng.uniform(-0.7, rows * RES + 0.5)),
            float(self.rng.uniform(-4.0, 4.0)),
        )
        chosen = _PARAMETERS[which]
        options: dict[str, Any] = {"exact": exact}
        if chosen is None:
            hit, miss, (low, high) = _DEFAULTS
        else:
            hit, miss, (low, high) = chosen
            options.update(hit=hit, miss=miss, clamp=(low, high))
        probe = OccupancyGrid(np.zeros(self.grid.shape), resolution=RES, origin=self.grid.origin)
        reached = probe.integrate_scan(
            scan, pose, hit=1.0, miss=-1.0, clamp=(-10.0, 10.0), exact=exact
        )
        hit_cells, miss_cells = probe.logodds > 0, probe.logodds < 0
        assert reached == int(hit_cells.sum() + miss_cells.sum())

        before = self.grid.logodds.astype(np.float64)
        assert self.grid.integrate_scan(scan, pose, **options) == reached
        after = self.grid.logodds.astype(np.float64)
        want = _updated(before, hit_cells, miss_cells, hit, miss, low, high)
        np.testing.assert_allclose(after, want, rtol=2e-7, atol=1e-6)
        untouched = ~(hit_cells | miss_cells)
        np.testing.assert_array_equal(after[untouched], before[untouched])
        self.model = after

    @rule(kind=st.sampled_from(["clamp", "hit", "miss", "pose", "scan", "exact"]))
    def refused(self, kind: str) -> None:
        scan: Any = LaserScan([1.0], angle_min=0.0, angle_increment=0.1, range_min=0.05,
                              range_max=3.0)
        refused_options: dict[str, dict[str, Any]] = {
            "clamp": {"clamp": (1.0, 1.0)},
            "hit": {"hit": -1.0},
            "miss": {"miss": 1.0},
            "exact": {"exact": 1},
        }
        options = refused_options.get(kind, {})
        pose = (math.nan, 0.0, 0.0) if kind == "pose" else (0.1, 0.1, 0.0)
        if kind == "scan":
            scan = [1.0]
        with pytest.raises((ValueError, TypeError)):
            self.grid.integrate_scan(scan, pose, **options)

    @rule(how=st.integers(0, len(_COPIERS) - 1))
    def swap_for_copy(self, how: int) -> None:
        old, self.grid = self.grid, _COPIERS[how](self.grid)
        np.testing.assert_array_equal(self.grid.logodds, old.logodds)
        rows, cols = old.shape
        # The original changing must not reach the copy (checked by the invariant).
        ring = LaserScan(np.full(8, 0.6), angle_min=-3.0, angle_increment=0.75, range_min=0.05,
                         range_max=3.0)
        old.integrate_scan(ring, (cols * RES / 2 + 0.3, rows * RES / 2 - 0.2, 0.0), hit=3.0,
                           miss=-3.0, clamp=(-9.0, 9.0))

    @invariant()
    def grid_is_the_model(self) -> None:
        logodds = self.grid.logodds
        assert logodds.dtype == np.float32
        assert not logodds.flags.writeable
        np.testing.assert_array_equal(logodds.astype(np.float64), self.model)


def test_scan_sequences_follow_the_update_rule() -> None:
    run_machine(GridMachine, examples=30, steps=15)


@pytest.mark.slow
def test_scan_sequences_follow_the_update_rule_long() -> None:
    run_machine(GridMachine, examples=400, steps=40)
