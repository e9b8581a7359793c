"""``indoor-nav``: the indoor-navigation robot's experiments in a 14.4 × 12 m lab.

Four parts, each beside the paper's figures:

(m) mapping — the lab's map built from simulated LiDAR scans on a mapping tour
    by :class:`~navkit.mapping.ScanMapper` (Hector-style scan matching, wheel
    odometry as the guess), as the paper built it with Hector mapping: room
    dimensions, agreement with the floor plan, trajectory error (with
    ``map_source="plan"`` the floor plan is rasterised instead);
(a) localisation — EKF fusion of wheel odometry and a 9-DoF IMU
    (:class:`~navkit.estimation.PlanarFusion`) against wheel odometry alone
    (:class:`~navkit.estimation.DiffOdometry`) over 10 target points;
(b) planning — Field D* against 8-connected A* on that map: path length,
    share of path headings that are not multiples of 45°, planning time;
(c) tracking — the ON-OFF tracker (:class:`~navkit.control.OnOffTracker`)
    along 4 Field D* paths: success rate and final errors.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from typing import Any, Literal, cast

import numpy as np

from navkit._shared.counts import counted
from navkit._shared.text import as_text
from navkit._shared.validation import as_bool, bounded_int, finite_float
from navkit.sim import Scenario, ScenarioResult, Scene, Table, Trace, Trial, TrialResult
from navkit.sim.scenarios._indoor_nav_lab import (
    LAB_HEIGHT,
    LAB_WIDTH,
    PLAN_ROUTES,
    ROOM_SPANS,
    SIDE_ROOM,
    TARGETS,
    TOUR_START,
    TRACK_PATHS,
    lab_grid,
    lab_world,
)
from navkit.sim.scenarios._indoor_nav_mapping import (
    MAP_SEED,
    MAP_SOURCES,
    MAPPING_SPEED,
    TURN_PER_SPEED,
    lab_map,
    lab_planner,
    mapping_values,
    plan_between,
    plan_inflation,
    room_spans,
    run_mapping,
    scan_map,
    span_key,
    tour_legs,
    track_route,
)
from navkit.sim.scenarios._indoor_nav_robot import (
    GYRO_NOISE,
    HEADING_NOISE,
    LIDAR,
    RADIUS_ERROR_SIGMA,
    SPEED,
    SUCCESS_RADIUS,
    TURN_RATE,
    WHEEL_SLIP,
)
from navkit.sim.scenarios._indoor_nav_runs import (
    run_localisation,
    run_planning,
    run_tracking,
)

__all__ = ["IndoorNav"]

MapSource = Literal["scans", "plan"]
"""``map_source``: the values of ``MAP_SOURCES``."""

#: The paper's mean localisation errors: x (m), y (m), heading (deg).
PAPER_WHEEL = (0.053, 0.043, 3.827)
PAPER_FUSED = (0.050, 0.028, 1.506)
#: The paper's ON-OFF tracking: final errors x (m), y (m), heading (deg); paths tracked.
PAPER_TRACKING = (0.046, 0.072, 5.163)
PAPER_TRACKED = (3, 4)
#: The paper's mean error on room dimensions of its Hector map, m; the speed above
#: which it found mapping degrading, m/s.
PAPER_ROOM_ERROR = 0.174
PAPER_MAPPING_SPEED = 0.2

#: Kinds of case, and the values each kind of trial has (what the tables read).
_MAPPING, _LOCALISATION, _PLANNING, _TRACKING = "mapping", "localisation", "planning", "tracking"
_KEYS = {
    _MAPPING: ("speed", "scans", "distance", "collisions", "unmatched", "room_error", "agreement",
               "coverage", "trajectory_mean", "trajectory_max", "trajectory_heading",
               "odometry_mean", "odometry_max", "odometry_heading", "match_wall_time",
               *(span_key(name) for name in ROOM_SPANS)),
    _LOCALISATION: ("targets_reached", "collisions", "distance", "wheel_x", "wheel_y",
                    "wheel_heading", "fused_x", "fused_y", "fused_heading"),
    _PLANNING: ("astar_length", "fdstar_length", "astar_off45", "fdstar_off45", "astar_wall_time",
                "fdstar_wall_time"),
    _TRACKING: ("tracked", "x", "y", "heading", "length"),
}  # fmt: skip
#: Slowest and fastest mapping tour of the comparison, m/s.
_SPEED_RANGE = (0.05, 1.0)


def _count(value: Any, name: str, high: int) -> int:
    """An integer in [1, high]."""
    return bounded_int(value, name, 1, high)


def _xy(point: Sequence[float]) -> str:
    return f"({point[0]:g}, {point[1]:g})"


def _mean(values: Sequence[float]) -> float:
    finite = [v for v in values if not math.isnan(v)]
    return float(np.mean(finite)) if finite else math.nan


class IndoorNav(Scenario):
    """The indoor-navigation robot: a map from scans, EKF localisation, Field D*, ON-OFF.

    The lab (built here from its floor plan as shapely boxes) is a 14.4 × 12 m
    room with a 4.8 × 4.4 m side room partitioned off in its north-east corner
    (1.0 m door) and, with ``furniture``, two lab benches, a table, shelves,
    cabinets and a desk; the simulated world is always this floor plan. The
    robot is a differential drive (0.40 m track, 75 mm wheels, 0.2 m body
    radius) whose true wheel radii are off by N(0, 0.2 %) and whose wheels
    slip (0.5 %), with 2048-tick encoders, a 9-DoF IMU (gyro, accelerometer
    and a magnetometer heading with 2° noise and a small bias) and a 360-beam
    10 Hz LiDAR (RPLIDAR A1 class, 1–2.5 % range noise).

    The map every experiment plans on (``map_source``): ``"scans"`` — built as
    the paper built it with Hector mapping: the robot drives a ~60 m mapping
    tour through the lab and the side room at 0.2 m/s and
    :class:`~navkit.mapping.ScanMapper` matches and writes every scan, wheel
    odometry giving the guesses (one tour, seed 0, whatever the run's seed:
    every trial plans on the same map); ``"plan"`` — the floor plan
    rasterised to an :class:`~navkit.mapping.OccupancyGrid`.

    Cases, in order:

    * localisation: a tour through ``targets`` target points, each leg planned
      by Field D* and followed by the ON-OFF tracker on the EKF estimate; at
      each target the fused estimate and wheel odometry alone (fed the same
      encoder readings) are compared with the true pose (``trials`` runs);
    * planning: Field D* against 8-connected A* on 8 routes, one trial each
      whatever ``trials`` is (obstacles inflated by 0.35 m on the floor plan;
      by 0.4 m, costs decaying out to 0.8 m, on the built map, whose walls lie
      up to ~0.2 m off);
    * ON-OFF tracking of the first ``paths`` of 4 Field D* paths on the EKF
      estimate (``trials`` runs each);
    * with ``map_source="scans"``, last (so that the other cases' seeds do not
      depend on the map source): mapping — the tour that builds the map (once),
      and with ``compare_speed`` the same tour at that speed (once, its map not
      used): room dimensions, agreement with the floor plan, trajectory errors.

    Every option is keyword-only.

    Parameters
    ----------
    targets : int, default 10
        Target points of the localisation tour, 1 to 10.
    paths : int, default 4
        Tracking paths, 1 to 4.
    furniture : bool, default True
        Furnish the lab.
    resolution : float, default 0.05
        Map cell size, m, in [0.025, 0.1].
    map_source : {"scans", "plan"}, default "scans"
        Build the map from simulated scans, or rasterise the floor plan.
    compare_speed : float or None, default 0.5
        Speed of a second mapping tour (m/s, in [0.05, 1], other than 0.2)
        beside the 0.2 m/s one; None for none. Only with ``map_source="scans"``.

    Raises
    ------
    TypeError
        ``targets`` or ``paths`` not an integer, ``furniture`` not a bool,
        ``resolution`` or ``compare_speed`` not a real number, ``map_source``
        not a str.
    ValueError
        An argument outside its range, an unknown ``map_source``, a
        ``compare_speed`` equal to the mapping tour's.

    Examples
    --------
    >>> scenario = IndoorNav(targets=1, paths=1, map_source="plan")
    >>> [count for _, count in scenario.cases(3)]
    [3, 8, 3]
    >>> [count for _, count in IndoorNav(targets=1, paths=1).cases(3)]
    [3, 8, 3, 1, 1]
    >>> result = scenario.run_trial(scenario.trials(1)[1])
    >>> result.values["fdstar_length"] < result.values["astar_length"]
    True
    """

    name = "indoor-nav"
    title = (
        "Map from simulated scans, EKF wheel odometry + IMU, Field D* vs A*, ON-OFF tracking "
        "in a 14.4 × 12 m lab"
    )
    paper = (
        "the indoor-navigation robot paper: a Hector map of the lab, EKF fusion of wheel "
        "odometry and a 9-DoF IMU (robot_localization), Field D* planning and an ON-OFF "
        "controller in a 14.4 × 12 m lab"
    )
    default_trials = 1

    def __init__(
        self,
        *,
        targets: int = 10,
        paths: int = 4,
        furniture: bool = True,
        resolution: float = 0.05,
        map_source: MapSource = "scans",
        compare_speed: float | None = 0.5,
    ) -> None:
        self.targets: int = _count(targets, "targets", len(TARGETS))
        self.paths: int = _count(paths, "paths", len(TRACK_PATHS))
        self.furniture: bool = as_bool(furniture, "furniture")
        res = finite_float(resolution, "resolution")
        if not 0.025 <= res <= 0.1:
            raise ValueError(f"resolution must lie in [0.025, 0.1] m, got {res}")
        self.resolution: float = res
        if not isinstance(map_source, str):
            raise TypeError(f"map_source must be a str, got {type(map_source).__name__}")
        source = as_text(map_source, "map_source")  # checked and kept as the plain str
        if source not in MAP_SOURCES:
            raise ValueError(f"map_source must be one of {MAP_SOURCES}, got {source!r}")
        self.map_source: MapSource = cast(MapSource, source)
        speed: float | None = None
        if compare_speed is not None:
            speed = finite_float(compare_speed, "compare_speed")
            if not _SPEED_RANGE[0] <= speed <= _SPEED_RANGE[1]:
                raise ValueError(
                    f"compare_speed must lie in [{_SPEED_RANGE[0]}, {_SPEED_RANGE[1]}] m/s, "
                    f"got {speed}"
                )
            if speed == MAPPING_SPEED:
                # The same tour twice: one case would hide the other (both "the map used").
                raise ValueError(
                    f"compare_speed must differ from the mapping tour's {MAPPING_SPEED:g} m/s "
                    "(None for no comparison)"
                )
        self.compare_speed: float | None = speed

    def __repr__(self) -> str:
        return (
            f"IndoorNav(targets={self.targets}, paths={self.paths}, "
            f"furniture={self.furniture}, resolution={self.resolution}, "
            f"map_source={self.map_source!r}, compare_speed={self.compare_speed})"
        )

    def _kinds(self) -> tuple[tuple[str, float], ...]:
        """Each case's kind and its parameter (mapping speed, tracking path index)."""
        kinds = [(_LOCALISATION, 0.0), (_PLANNING, 0.0)]
        kinds += [(_TRACKING, float(k)) for k in range(self.paths)]
        if self.map_source == "scans":
            # Last, so that the other cases' seeds do not depend on the map source.
            kinds.append((_MAPPING, MAPPING_SPEED))
            if self.compare_speed is not None:
                kinds.append((_MAPPING, self.compare_speed))
        return tuple(kinds)

    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        """Localisation, planning (8 routes, once each), tracking paths, mapping (once each).

        Parameters
        ----------
        trials : int
            Runs of the localisation tour and of each tracking path, >= 1.

        Returns
        -------
        tuple of (str, int)
            ``(case, number of trials)``.

        Examples
        --------
        >>> IndoorNav(paths=2).cases(5)[2:4]
        (('ON-OFF tracking, path 1', 5), ('ON-OFF tracking, path 2', 5))
        >>> IndoorNav(paths=2).cases(5)[4]
        ('mapping: ScanMapper on the mapping tour at 0.2 m/s (the map used)', 1)
        """
        n = self._check_trials(trials)
        out = []
        for kind, param in self._kinds():
            if kind == _MAPPING:
                used = " (the map used)" if param == MAPPING_SPEED else " (for comparison)"
                out.append((f"mapping: ScanMapper on the mapping tour at {param:g} m/s{used}", 1))
            elif kind == _LOCALISATION:
                out.append((f"localisation: wheel odometry vs EKF fusion, "
                            f"{counted(self.targets, 'target')}", n))  # fmt: skip
            elif kind == _PLANNING:
                out.append(("planning: Field D* vs 8-connected A*", len(PLAN_ROUTES)))
            else:
                out.append((f"ON-OFF tracking, path {int(param) + 1}", n))
        return tuple(out)

    def run_trial(self, trial: Trial) -> TrialResult:
        """Run one trial (see :meth:`cases`); depends only on the options and ``trial``.

        Parameters
        ----------
        trial : Trial
            Which case, which trial (for planning: which route) and the seed
            (the mapping tours run with the fixed seed 0).

        Returns
        -------
        TrialResult
            Values in SI units (headings in rad); the simulated runs' traces.

        Examples
        --------
        >>> scenario = IndoorNav(resolution=0.1, map_source="plan")
        >>> r = scenario.run_trial(Trial("planning", 1, 0, 0))
        >>> r.values["astar_off45"], r.values["fdstar_off45"] > 0.0
        (0.0, True)
        """
        kind, param = self._kinds()[self._case_of(trial)]
        index, seed = trial.index, trial.seed
        res, furn, source = self.resolution, self.furniture, self.map_source
        t0 = time.perf_counter()
        trace: Trace | None = None
        if kind == _MAPPING:
            if param == MAPPING_SPEED:
                run = scan_map(res, furn)
            else:
                run = run_mapping(MAP_SEED, resolution=res, furniture=furn, speed=param)
            values, trace = mapping_values(run, resolution=res, furniture=furn), run.trace
        elif kind == _LOCALISATION:
            values, trace = run_localisation(
                seed, resolution=res, furniture=furn, targets=self.targets, source=source
            )
        elif kind == _PLANNING:
            if index >= len(PLAN_ROUTES):
                raise ValueError(
                    f"trial.index must be below {len(PLAN_ROUTES)} for the planning case, "
                    f"got {index}"
                )
            values, _ = run_planning(index, resolution=res, furniture=furn, source=source)
        else:
            values, trace = run_tracking(
                seed, int(param), resolution=res, furniture=furn, source=source
            )
        return TrialResult(trial, values, trace, time.perf_counter() - t0)

    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
        """Tables beside the paper's: mapping, localisation errors, planning, tracking.

        Parameters
        ----------
        results : sequence of TrialResult
            The trials of :meth:`trials`, in order.
        seed : int
            The base seed.

        Returns
        -------
        ScenarioResult
            Four tables (three with ``map_source="plan"``), the headline
            ``summary`` (SI units, headings in rad; the ``*_wall_time``
            figures are wall-clock and vary from run to run) and a scene.

        Examples
        --------
        >>> scenario = IndoorNav(resolution=0.1, map_source="plan")
        >>> trials = [t for t in scenario.trials(1) if t.case_index == 1]
        >>> result = scenario.summarize([scenario.run_trial(t) for t in trials], seed=0)
        >>> result.summary["fdstar_length"] < result.summary["astar_length"]
        True
        """
        kinds = self._kinds()
        items, by_case, base = self._results_by_case(
            results, seed, keys=lambda case: _KEYS[kinds[case][0]]
        )
        for k, r in enumerate(items):
            if kinds[r.trial.case_index][0] == _PLANNING and r.trial.index >= len(PLAN_ROUTES):
                raise ValueError(
                    f"results[{k}].trial.index must be below {len(PLAN_ROUTES)} for the planning "
                    f"case, got {r.trial.index}"
                )
        by_kind = {kinds[case]: runs for case, runs in by_case.items()}
        summary: dict[str, float] = {}
        tables = []
        if self.map_source == "scans":
            tables.append(self._mapping_table(by_kind, summary))
        tables += [
            self._localisation_table(by_kind.get((_LOCALISATION, 0.0), []), summary),
            self._planning_table(by_kind.get((_PLANNING, 0.0), []), summary),
            self._tracking_table(by_kind, summary),
        ]
        return ScenarioResult(
            scenario=self.name, seed=base, trials=items, tables=tuple(tables),
            summary=summary, scene=self._scene(by_kind),
        )  # fmt: skip

    # ----------------------------------------------------------------- tables
    def _map_note(self) -> str:
        if self.map_source == "plan":
            return (
                "The map is the floor plan rasterised to an occupancy grid (map_source='plan'); "
                "by default it is built from simulated scans (table (a))."
            )
        return (
            "Planned on the map built from simulated scans by scan matching (table (a)); the "
            "simulated world is the true floor plan."
        )

    def _mapping_table(
        self, by_kind: dict[tuple[str, float], list[TrialResult]], summary: dict[str, float]
    ) -> Table:
        speeds = [MAPPING_SPEED]
        if self.compare_speed is not None and self.compare_speed != MAPPING_SPEED:
            speeds.append(self.compare_speed)
        runs = [by_kind.get((_MAPPING, v), []) for v in speeds]

        def col(key: str, scale: float = 1.0) -> list[float]:
            return [scale * _mean([r.values[key] for r in rr]) for rr in runs]

        plan = room_spans(lab_grid(self.resolution, self.furniture))
        plan_error = _mean([abs(plan[n] - spec[0]) for n, spec in ROOM_SPANS.items()])
        rows: list[tuple[Any, ...]] = []
        for name, spec in ROOM_SPANS.items():
            rows.append((f"{name} (m)", *col(span_key(name)), plan[name], spec[0], None))
        rows += [
            ("mean error on room dimensions (m)", *col("room_error"), plan_error, 0.0,
             PAPER_ROOM_ERROR),
            ("cell agreement with the floor plan (%)", *col("agreement", 100.0), 100.0, None,
             None),
            ("floor plan's free cells mapped free (%)", *col("coverage", 100.0), 100.0, None,
             None),
            ("trajectory error, mean (m)", *col("trajectory_mean"), None, None, None),
            ("trajectory error, max (m)", *col("trajectory_max"), None, None, None),
            ("heading error, mean (deg)", *col("trajectory_heading", 180.0 / math.pi), None, None,
             None),
            ("wheel odometry (the guess) error, mean (m)", *col("odometry_mean"), None, None,
             None),
            ("wheel odometry heading error, mean (deg)", *col("odometry_heading", 180.0 / math.pi),
             None, None, None),
            ("scans (unmatched)", *[f"{a:.0f} ({b:.0f})" for a, b in
                                    zip(col("scans"), col("unmatched"), strict=True)], None,
             None, None),
            ("tour length (m), collisions", *[f"{a:.1f}, {b:.0f}" for a, b in
                                              zip(col("distance"), col("collisions"),
                                                  strict=True)], None, None, None),
            ("match + write per scan (ms, wall)", *col("match_wall_time", 1e3), None, None, None),
        ]  # fmt: skip
        for prefix, rr in zip(("map", "compare"), runs, strict=False):
            for key in ("room_error", "agreement", "coverage", "trajectory_mean",
                        "trajectory_max", "trajectory_heading", "odometry_mean"):  # fmt: skip
                summary[f"{prefix}_{key}"] = _mean([r.values[key] for r in rr])
            summary[f"{prefix}_match_wall_time"] = _mean([r.values["match_wall_time"] for r in rr])
        columns = (
            "figure", *(f"built at {v:g} m/s" for v in speeds), "floor plan rasterised",
            "true (plan)", "paper",
        )  # fmt: skip
        notes = (
            f"The map every experiment plans on: built from the scans of one mapping tour at "
            f"{MAPPING_SPEED:g} m/s (seed {MAP_SEED}, ~60 m through the lab and, through its "
            f"door, the side room; ON-OFF on the EKF estimate, turning at "
            f"{TURN_PER_SPEED * MAPPING_SPEED:g} rad/s) by ScanMapper: Hector's loop — every scan "
            "matched to the map so far by Gauss–Newton on three map levels from the wheel "
            f"odometry's guess, written in after 0.4 m or 0.9 rad — at {self.resolution:g} m "
            "cells. LiDAR: "
            f"{LIDAR.n_beams} beams, {LIDAR.rate:g} Hz, {LIDAR.range_max:g} m, range noise "
            "1 % (< 3 m), 2 % (< 5 m), 2.5 % (RPLIDAR A1 datasheet; the paper does not name "
            "its scanner).",
            "Room dimensions: inside spans, wall face to wall face (lab 14.2 × 11.8 m, side room "
            "4.7 × 4.3 m inside its 0.1 m walls), measured on the map along 4–6 lines clear of "
            "furniture (median), a wall face at the centre of the first occupied cell. The "
            "rasterised plan's spans show the grid's own error (a cell touching a wall is "
            "occupied). The paper reports 0.174 m mean error on room dimensions for its map.",
            "Cell agreement: share of the floor plan's cells known on the built map (occupied "
            "or free) on which both agree; walls drawn a cell thicker or thinner count "
            "against it. Trajectory errors: the mapper's pose at every scan against the true "
            "pose (no alignment: the map starts at the true start pose).",
            f"The paper found mapping degrading above {PAPER_MAPPING_SPEED:g} m/s on its "
            "embedded computer (scans arriving faster than Hector processed them); here every "
            "scan is processed whatever the speed, so a faster tour only moves further between "
            "scans and takes fewer of them.",
        )
        return Table(
            "(a) Mapping: the lab's map built from simulated scans (Hector-style scan matching)",
            columns, tuple(rows), notes,
        )  # fmt: skip

    def _localisation_table(self, runs: list[TrialResult], summary: dict[str, float]) -> Table:
        rows: list[tuple[Any, ...]] = []
        for key, label, paper in (
            ("wheel", "wheel odometry", PAPER_WHEEL),
            ("fused", "EKF: wheels + IMU", PAPER_FUSED),
        ):
            x = _mean([r.values[f"{key}_x"] for r in runs])
            y = _mean([r.values[f"{key}_y"] for r in runs])
            heading = _mean([r.values[f"{key}_heading"] for r in runs])
            summary.update({f"{key}_x": x, f"{key}_y": y, f"{key}_heading": heading})
            rows.append((label, x, y, math.degrees(heading), *paper))
        reached = sum(r.values["targets_reached"] for r in runs)
        collisions = sum(r.values["collisions"] for r in runs)
        distance = _mean([r.values["distance"] for r in runs])
        summary["targets_reached"] = float(reached) / max(len(runs), 1)
        notes = (
            f"Mean absolute error of the pose estimate at the "
            f"{counted(self.targets, 'target point')}, over {len(runs)} run(s) of the tour "
            f"({distance:.1f} m each; {counted(round(reached), 'target arrival')}, "
            f"{counted(round(collisions), 'collision')}).",
            "One run feeds both estimates the same encoder readings; the robot drives "
            "(ON-OFF along Field D* legs) on the EKF estimate. Wheels: true radii off by "
            f"N(0, {RADIUS_ERROR_SIGMA:.1%}), slip {WHEEL_SLIP:.1%}; IMU: gyro "
            f"{GYRO_NOISE} rad/s, magnetometer heading {math.degrees(HEADING_NOISE):.0f}° "
            "noise with a small bias. The paper's tour and wheel errors are not published.",
            self._map_note(),
        )
        return Table(
            "(b) Localisation: wheel odometry against EKF fusion of wheel odometry and IMU",
            ("estimate", "x (m)", "y (m)", "heading (deg)", "paper x (m)", "paper y (m)",
             "paper heading (deg)"),
            tuple(rows), notes,
        )  # fmt: skip

    def _planning_table(self, runs: list[TrialResult], summary: dict[str, float]) -> Table:
        rows: list[tuple[Any, ...]] = []
        for r in sorted(runs, key=lambda r: r.trial.index):
            v = r.values
            start, goal = PLAN_ROUTES[r.trial.index]
            rows.append((
                f"{_xy(start)} → {_xy(goal)}", v["astar_length"], v["fdstar_length"],
                100.0 * v["astar_off45"], 100.0 * v["fdstar_off45"],
                1e3 * v["astar_wall_time"], 1e3 * v["fdstar_wall_time"],
            ))  # fmt: skip
        total = {}
        for key in ("astar", "fdstar"):
            total[key] = float(sum(r.values[f"{key}_length"] for r in runs)) if runs else math.nan
            summary[f"{key}_length"] = total[key]
            summary[f"{key}_off45"] = _mean([r.values[f"{key}_off45"] for r in runs])
        shorter = sum(r.values["fdstar_length"] < r.values["astar_length"] for r in runs)
        summary["fdstar_shorter"] = float(shorter) / max(len(runs), 1)
        for key in ("astar", "fdstar"):
            summary[f"{key}_wall_time"] = _mean([r.values[f"{key}_wall_time"] for r in runs])
        rows.append((
            "all routes (sum; mean %; mean ms)", total["astar"], total["fdstar"],
            100.0 * summary["astar_off45"], 100.0 * summary["fdstar_off45"],
            1e3 * summary["astar_wall_time"], 1e3 * summary["fdstar_wall_time"],
        ))  # fmt: skip
        saving = 100.0 * (1.0 - total["fdstar"] / total["astar"]) if runs else math.nan
        radius, inflation = plan_inflation(self.map_source)
        costs = f"obstacles inflated by {radius:g} m"
        if inflation > radius:
            costs += (
                f", costs decaying out to {inflation:g} m: more clearance on the built map, "
                "whose walls lie up to ~0.2 m off (the plan's 0.35 m alone lets the "
                "localisation tour graze a bench)"
            )
        notes = (
            f"Field D* is {saving:.1f} % shorter in all and shorter on {shorter} of {len(runs)} "
            "routes; headings: share of path segments whose heading is not a multiple of 45°.",
            f"Both plan on the same costs ({self.resolution:g} m cells, {costs}); times are "
            "the best of 3 searches from "
            "scratch (wall clock, they vary from run to run; Field D* includes its shortcut "
            "pass).",
            "The paper chose Field D* for its unrestricted headings and shorter, smoother "
            "paths; it gives no lengths or times to compare with.",
            self._map_note(),
        )
        return Table(
            "(c) Planning on the lab map: Field D* against 8-connected A*",
            ("route (m)", "A* length (m)", "Field D* length (m)", "A* non-45° (%)",
             "Field D* non-45° (%)", "A* time (ms, wall)", "Field D* time (ms, wall)"),
            tuple(rows), notes,
        )  # fmt: skip

    def _tracking_table(
        self, by_kind: dict[tuple[str, float], list[TrialResult]], summary: dict[str, float]
    ) -> Table:
        rows: list[tuple[Any, ...]] = []
        every: list[TrialResult] = []
        for k in range(self.paths):
            runs = by_kind.get((_TRACKING, float(k)), [])
            every += runs
            start, goal = TRACK_PATHS[k]
            tracked = sum(r.values["tracked"] for r in runs)
            rows.append((
                f"{k + 1}: {_xy(start)} → {_xy(goal)}",
                _mean([r.values["length"] for r in runs]), f"{tracked:.0f} of {len(runs)}",
                _mean([r.values["x"] for r in runs]), _mean([r.values["y"] for r in runs]),
                math.degrees(_mean([r.values["heading"] for r in runs])),
            ))  # fmt: skip
        ok = [r for r in every if r.values["tracked"] == 1.0]
        rate = len(ok) / len(every) if every else math.nan
        summary["tracking_success_rate"] = rate
        for axis in ("x", "y", "heading"):
            summary[f"tracking_{axis}"] = _mean([r.values[axis] for r in ok])
        rows.append((
            "tracked runs", math.nan, f"{len(ok)} of {len(every)}", summary["tracking_x"],
            summary["tracking_y"], math.degrees(summary["tracking_heading"]),
        ))  # fmt: skip
        rows.append((
            "paper", math.nan, f"{PAPER_TRACKED[0]} of {PAPER_TRACKED[1]}", *PAPER_TRACKING,
        ))  # fmt: skip
        notes = (
            "Final errors: true final pose against the goal pose (mean absolute x, y, heading); "
            "per path over all runs, in the 'tracked runs' row over the tracked ones.",
            f"Tracked: the tracker finished (goal within 0.05 m and goal heading on its EKF "
            f"estimate) without collision, and the true position ends within "
            f"{SUCCESS_RADIUS} m of the goal. ON-OFF: turn in place at {TURN_RATE} rad/s "
            f"until the heading error is below 10°, then straight at {SPEED} m/s.",
            "The paths are planned by Field D* on the lab map; the paper's four paths are "
            "not published.",
            self._map_note(),
        )
        return Table(
            "(d) ON-OFF tracking along Field D* paths on the EKF estimate",
            ("path (m)", "length (m)", "tracked", "x error (m)", "y error (m)",
             "heading error (deg)"),
            tuple(rows), notes,
        )  # fmt: skip

    def _scene(self, by_kind: dict[tuple[str, float], list[TrialResult]]) -> Scene:
        res, furn, source = self.resolution, self.furniture, self.map_source
        paths: list[tuple[str, Any]] = []
        astar = plan_between(lab_planner(res, furn, "astar", source), *PLAN_ROUTES[1])
        fdstar = plan_between(lab_planner(res, furn, "field_dstar", source), *PLAN_ROUTES[1])
        paths += [("A* (route 2)", astar.points), ("Field D* (route 2)", fdstar.points)]
        tour = np.vstack([leg.points for leg in tour_legs(res, furn, self.targets, source)])
        paths.append(("tour (Field D* legs)", tour))
        paths += [
            (f"tracking path {k + 1}", track_route(res, furn, k, source).points)
            for k in range(self.paths)
        ]
        traces: list[tuple[str, Trace]] = []
        for label, key in (
            (f"mapping tour at {MAPPING_SPEED:g} m/s: true, EKF", (_MAPPING, MAPPING_SPEED)),
            ("tour: true, EKF estimate", (_LOCALISATION, 0.0)),
            *((f"ON-OFF, path {k + 1}", (_TRACKING, float(k))) for k in range(self.paths)),
        ):
            runs = by_kind.get(key, [])
            if runs and runs[0].trace is not None:
                traces.append((label, runs[0].trace))
        points = (
            ("targets", np.array(TARGETS[: self.targets])),
            ("tour start", np.array([TOUR_START[:2]])),
            ("tracking goals", np.array([g[:2] for _, g in TRACK_PATHS[: self.paths]])),
        )
        room = f"{SIDE_ROOM[2] - SIDE_ROOM[0]:g} × {SIDE_ROOM[3] - SIDE_ROOM[1]:g} m side room"
        built = ", map built from simulated scans" if source == "scans" else ""
        return Scene(
            f"indoor-nav: {LAB_WIDTH:g} × {LAB_HEIGHT:g} m lab with a {room}{built}",
            grid=lab_map(res, furn, source), world=lab_world(furn), paths=tuple(paths),
            traces=tuple(traces), points=points,
        )  # fmt: skip
