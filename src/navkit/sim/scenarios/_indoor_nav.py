"""``indoor-nav``: the indoor-navigation robot's experiments in a 14.4 × 12 m lab.

Three parts, each beside the paper's figures:

(a) localisation — EKF fusion of wheel odometry and a 9-DoF IMU
    (:class:`~navkit.estimation.PlanarFusion`) against wheel odometry alone
    (:class:`~navkit.estimation.DiffOdometry`) over 10 target points;
(b) planning — Field D* against 8-connected A* on the lab map: path length,
    share of path headings that are not multiples of 45°, planning time;
(c) tracking — the ON-OFF tracker (:class:`~navkit.control.OnOffTracker`)
    along 4 Field D* paths: success rate and final errors.
"""

from __future__ import annotations

import math
import numbers
import time
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from navkit._shared.validation import as_bool, finite_float
from navkit.sim import Scenario, ScenarioResult, Scene, Table, Trace, Trial, TrialResult
from navkit.sim.scenarios._indoor_nav_lab import (
    LAB_HEIGHT,
    LAB_WIDTH,
    PLAN_RADIUS,
    PLAN_ROUTES,
    SIDE_ROOM,
    TARGETS,
    TOUR_START,
    TRACK_PATHS,
    lab_grid,
    lab_planner,
    lab_world,
    tour_legs,
    track_route,
)
from navkit.sim.scenarios._indoor_nav_runs import (
    GYRO_NOISE,
    HEADING_NOISE,
    RADIUS_ERROR_SIGMA,
    SPEED,
    SUCCESS_RADIUS,
    TURN_RATE,
    WHEEL_SLIP,
    run_localisation,
    run_planning,
    run_tracking,
)

__all__ = ["IndoorNav"]

#: The paper's mean localisation errors: x (m), y (m), heading (deg).
PAPER_WHEEL = (0.053, 0.043, 3.827)
PAPER_FUSED = (0.050, 0.028, 1.506)
#: The paper's ON-OFF tracking: final errors x (m), y (m), heading (deg); paths tracked.
PAPER_TRACKING = (0.046, 0.072, 5.163)
PAPER_TRACKED = (3, 4)

_LOCALISATION = 0
_PLANNING = 1
_TRACKING = 2  # first tracking case; one case per path

#: The values each kind of trial has (what the tables read).
_KEYS = {
    _LOCALISATION: ("targets_reached", "collisions", "distance", "wheel_x", "wheel_y",
                    "wheel_heading", "fused_x", "fused_y", "fused_heading"),
    _PLANNING: ("astar_length", "fdstar_length", "astar_off45", "fdstar_off45", "astar_wall_time",
                "fdstar_wall_time"),
    _TRACKING: ("tracked", "x", "y", "heading", "length"),
}  # fmt: skip

_MAP_NOTE = (
    "The map is given (the floor plan rasterised to an occupancy grid); issue 14 asks for "
    "it to be built from simulated scans once scan matching lands — not done yet."
)


def _count(value: Any, name: str, high: int) -> int:
    """An integer in [1, high]."""
    out = _index(value, name, None)
    if not 1 <= out <= high:
        raise ValueError(f"{name} must lie in [1, {high}], got {out}")
    return out


def _xy(point: Sequence[float]) -> str:
    return f"({point[0]:g}, {point[1]:g})"


def _mean(values: Sequence[float]) -> float:
    finite = [v for v in values if not math.isnan(v)]
    return float(np.mean(finite)) if finite else math.nan


class IndoorNav(Scenario):
    """The indoor-navigation robot: EKF localisation, Field D* against A*, ON-OFF tracking.

    The lab (built here from its floor plan as shapely boxes, and rasterised
    to an :class:`~navkit.mapping.OccupancyGrid`) is a 14.4 × 12 m room with a
    4.8 × 4.4 m side room partitioned off in its north-east corner (1.0 m
    door) and, with ``furniture``, two lab benches, a table, shelves, cabinets
    and a desk. The robot is a differential drive (0.40 m track, 75 mm wheels,
    0.2 m body radius) whose true wheel radii are off by N(0, 0.2 %) and whose
    wheels slip (0.5 %), with 2048-tick encoders and a 9-DoF IMU (gyro,
    accelerometer and a magnetometer heading with 2° noise and a small bias).

    Cases, in order:

    0. localisation: a tour through ``targets`` target points, each leg planned
       by Field D* and followed by the ON-OFF tracker on the EKF estimate; at
       each target the fused estimate and wheel odometry alone (fed the same
       encoder readings) are compared with the true pose (``trials`` runs);
    1. planning: Field D* against 8-connected A* (0.35 m inflation) on 8
       routes, one trial each whatever ``trials`` is;
    2. … : ON-OFF tracking of the first ``paths`` of 4 Field D* paths on the
       EKF estimate (``trials`` runs each).

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

    Examples
    --------
    >>> scenario = IndoorNav(targets=1, paths=1)
    >>> [count for _, count in scenario.cases(3)]
    [3, 8, 3]
    >>> result = IndoorNav(resolution=0.1).run_trial(scenario.trials(1)[1])
    >>> result.values["fdstar_length"] < result.values["astar_length"]
    True
    """

    name = "indoor-nav"
    title = "EKF wheel odometry + IMU, Field D* against A*, ON-OFF tracking in a 14.4 × 12 m lab"
    paper = (
        "the indoor-navigation robot paper: EKF fusion of wheel odometry and a 9-DoF IMU "
        "(robot_localization), Field D* planning and an ON-OFF controller in a 14.4 × 12 m lab"
    )
    default_trials = 1

    def __init__(
        self,
        *,
        targets: int = 10,
        paths: int = 4,
        furniture: bool = True,
        resolution: float = 0.05,
    ) -> None:
        self.targets = _count(targets, "targets", len(TARGETS))
        self.paths = _count(paths, "paths", len(TRACK_PATHS))
        self.furniture = as_bool(furniture, "furniture")
        res = finite_float(resolution, "resolution")
        if not 0.025 <= res <= 0.1:
            raise ValueError(f"resolution must lie in [0.025, 0.1] m, got {res}")
        self.resolution: float = res

    def __repr__(self) -> str:
        return (
            f"IndoorNav(targets={self.targets}, paths={self.paths}, "
            f"furniture={self.furniture}, resolution={self.resolution})"
        )

    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        """Localisation, planning (8 routes, once each), then one case per tracking path.

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
        >>> IndoorNav(paths=2).cases(5)[2:]
        (('ON-OFF tracking, path 1', 5), ('ON-OFF tracking, path 2', 5))
        """
        n = _count(trials, "trials", 100_000)
        out = [
            (f"localisation: wheel odometry vs EKF fusion, {self.targets} targets", n),
            ("planning: Field D* vs 8-connected A*", len(PLAN_ROUTES)),
        ]
        out += [(f"ON-OFF tracking, path {k + 1}", n) for k in range(self.paths)]
        return tuple(out)

    def run_trial(self, trial: Trial) -> TrialResult:
        """Run one trial (see :meth:`cases`); depends only on the options and ``trial``.

        Parameters
        ----------
        trial : Trial
            Which case, which trial (for planning: which route) and the seed.

        Returns
        -------
        TrialResult
            Values in SI units (headings in rad); the simulated runs' traces.

        Examples
        --------
        >>> scenario = IndoorNav(resolution=0.1)
        >>> r = scenario.run_trial(Trial("planning", 1, 0, 0))
        >>> r.values["astar_off45"], r.values["fdstar_off45"] > 0.0
        (0.0, True)
        """
        if not isinstance(trial, Trial):
            raise TypeError(f"trial must be a Trial, got {type(trial).__name__}")
        case = _index(trial.case_index, "trial.case_index", _TRACKING + self.paths)
        index = _index(trial.index, "trial.index", None)
        seed = _index(trial.seed, "trial.seed", 1 << 64)
        res, furn = self.resolution, self.furniture
        t0 = time.perf_counter()
        trace: Trace | None = None
        if case == _LOCALISATION:
            values, trace = run_localisation(
                seed, resolution=res, furniture=furn, targets=self.targets
            )
        elif case == _PLANNING:
            if index >= len(PLAN_ROUTES):
                raise ValueError(
                    f"trial.index must be below {len(PLAN_ROUTES)} for the planning case, "
                    f"got {index}"
                )
            values, _ = run_planning(index, resolution=res, furniture=furn)
        else:
            values, trace = run_tracking(seed, case - _TRACKING, resolution=res, furniture=furn)
        return TrialResult(trial, values, trace, time.perf_counter() - t0)

    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
        """Tables beside the paper's: localisation errors, planning, tracking.

        Parameters
        ----------
        results : sequence of TrialResult
            The trials of :meth:`trials`, in order.
        seed : int
            The base seed.

        Returns
        -------
        ScenarioResult
            Three tables, the headline ``summary`` (SI units, headings in rad;
            the planning times, ``*_wall_time``, are wall-clock and vary from
            run to run) and a scene.

        Examples
        --------
        >>> scenario = IndoorNav(resolution=0.1)
        >>> trials = [t for t in scenario.trials(1) if t.case_index == 1]
        >>> result = scenario.summarize([scenario.run_trial(t) for t in trials], seed=0)
        >>> result.summary["fdstar_length"] < result.summary["astar_length"]
        True
        """
        base = _index(seed, "seed", 1 << 64)
        items = self._checked(results)
        by_case: dict[int, list[TrialResult]] = {}
        for r in items:
            by_case.setdefault(r.trial.case_index, []).append(r)
        summary: dict[str, float] = {}
        tables = (
            self._localisation_table(by_case.get(_LOCALISATION, []), summary),
            self._planning_table(by_case.get(_PLANNING, []), summary),
            self._tracking_table(by_case, summary),
        )
        return ScenarioResult(
            scenario=self.name, seed=base, trials=items, tables=tables,
            summary=summary, scene=self._scene(by_case),
        )  # fmt: skip

    def _checked(self, results: Any) -> tuple[TrialResult, ...]:
        """``results`` as a tuple, each of a known case with the values its tables read."""
        if isinstance(results, (str, bytes)) or not isinstance(results, Sequence):
            raise TypeError(f"results must be a sequence of TrialResult, got {type(results)}")
        items = tuple(results)
        for i, r in enumerate(items):
            if not isinstance(r, TrialResult) or not isinstance(r.trial, Trial):
                raise TypeError(f"results[{i}] must be a TrialResult, got {type(r).__name__}")
            case = _index(r.trial.case_index, f"results[{i}].trial.case_index",
                          _TRACKING + self.paths)  # fmt: skip
            keys = _KEYS[min(case, _TRACKING)]
            values = r.values
            if case == _PLANNING:
                _index(r.trial.index, f"results[{i}].trial.index", len(PLAN_ROUTES))
            if not isinstance(values, Mapping) or not all(
                isinstance(values.get(k), (float, int)) and not isinstance(values.get(k), bool)
                for k in keys
            ):
                raise ValueError(f"results[{i}].values must hold the numbers {', '.join(keys)}")
        return items

    # ----------------------------------------------------------------- tables
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
            f"Mean absolute error of the pose estimate at the {self.targets} target points, "
            f"over {len(runs)} run(s) of the tour ({distance:.1f} m each; "
            f"{reached:.0f} target arrivals, {collisions:.0f} collisions).",
            "One run feeds both estimates the same encoder readings; the robot drives "
            "(ON-OFF along Field D* legs) on the EKF estimate. Wheels: true radii off by "
            f"N(0, {RADIUS_ERROR_SIGMA:.1%}), slip {WHEEL_SLIP:.1%}; IMU: gyro "
            f"{GYRO_NOISE} rad/s, magnetometer heading {math.degrees(HEADING_NOISE):.0f}° "
            "noise with a small bias. The paper's tour and wheel errors are not published.",
            _MAP_NOTE,
        )
        return Table(
            "(a) Localisation: wheel odometry against EKF fusion of wheel odometry and IMU",
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
        notes = (
            f"Field D* is {saving:.1f} % shorter in all and shorter on {shorter} of {len(runs)} "
            "routes; headings: share of path segments whose heading is not a multiple of 45°.",
            f"Both plan on the same costs ({self.resolution:g} m cells, obstacles inflated by "
            f"{PLAN_RADIUS} m); times are the best of 3 searches from scratch (wall clock, "
            "they vary from run to run; Field D* includes its shortcut pass).",
            "The paper chose Field D* for its unrestricted headings and shorter, smoother "
            "paths; it gives no lengths or times to compare with.",
            _MAP_NOTE,
        )
        return Table(
            "(b) Planning on the lab map: Field D* against 8-connected A*",
            ("route (m)", "A* length (m)", "Field D* length (m)", "A* non-45° (%)",
             "Field D* non-45° (%)", "A* time (ms, wall)", "Field D* time (ms, wall)"),
            tuple(rows), notes,
        )  # fmt: skip

    def _tracking_table(
        self, by_case: dict[int, list[TrialResult]], summary: dict[str, float]
    ) -> Table:
        rows: list[tuple[Any, ...]] = []
        every: list[TrialResult] = []
        for k in range(self.paths):
            runs = by_case.get(_TRACKING + k, [])
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
            _MAP_NOTE,
        )
        return Table(
            "(c) ON-OFF tracking along Field D* paths on the EKF estimate",
            ("path (m)", "length (m)", "tracked", "x error (m)", "y error (m)",
             "heading error (deg)"),
            tuple(rows), notes,
        )  # fmt: skip

    def _scene(self, by_case: dict[int, list[TrialResult]]) -> Scene:
        res, furn = self.resolution, self.furniture
        paths: list[tuple[str, Any]] = []
        astar = lab_planner(res, furn, "astar").plan(*PLAN_ROUTES[1])
        fdstar = lab_planner(res, furn, "field_dstar").plan(*PLAN_ROUTES[1])
        paths += [("A* (route 2)", astar.points), ("Field D* (route 2)", fdstar.points)]
        tour = np.vstack([leg.points for leg in tour_legs(res, furn, self.targets)])
        paths.append(("tour (Field D* legs)", tour))
        paths += [
            (f"tracking path {k + 1}", track_route(res, furn, k).points) for k in range(self.paths)
        ]
        traces: list[tuple[str, Trace]] = []
        loc = by_case.get(_LOCALISATION, [])
        if loc and loc[0].trace is not None:
            traces.append(("tour: true, EKF estimate", loc[0].trace))
        for k in range(self.paths):
            runs = by_case.get(_TRACKING + k, [])
            if runs and runs[0].trace is not None:
                traces.append((f"ON-OFF, path {k + 1}", runs[0].trace))
        points = (
            ("targets", np.array(TARGETS[: self.targets])),
            ("tour start", np.array([TOUR_START[:2]])),
            ("tracking goals", np.array([g[:2] for _, g in TRACK_PATHS[: self.paths]])),
        )
        room = f"{SIDE_ROOM[2] - SIDE_ROOM[0]:g} × {SIDE_ROOM[3] - SIDE_ROOM[1]:g} m side room"
        return Scene(
            f"indoor-nav: {LAB_WIDTH:g} × {LAB_HEIGHT:g} m lab with a {room}",
            grid=lab_grid(res, furn), world=lab_world(furn), paths=tuple(paths),
            traces=tuple(traces), points=points,
        )  # fmt: skip


def _index(value: Any, name: str, high: int | None) -> int:
    """A non-negative integer below ``high`` (None: no bound)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name} must be an integer, got {type(value).__name__}")
    out = int(value)
    if out < 0 or (high is not None and out >= high):
        bound = f"[0, {high})" if high is not None else ">= 0"
        raise ValueError(f"{name} must be {bound}, got {out}")
    return out
