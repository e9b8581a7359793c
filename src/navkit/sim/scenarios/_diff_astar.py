"""diff-astar: the differential delivery robot, A* + follow-the-carrot in a house and a building."""

from __future__ import annotations

import itertools
import math
import os
import statistics
import time
from collections.abc import Sequence
from typing import Any, Literal, cast

import numpy as np
import shapely

from navkit._shared.text import as_text
from navkit._shared.validation import as_bool, positive_float
from navkit.control import FollowTheCarrot
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive
from navkit.planning import MapPlanner, Path2D
from navkit.sim import (
    Lidar,
    Observation,
    Robot,
    Scenario,
    ScenarioResult,
    Scene,
    Simulation,
    Table,
    Trace,
    TrackerController,
    Trial,
    TrialResult,
    WheelEncoders,
)
from navkit.sim.scenarios._diff_astar_localizer import ScanLocalizer
from navkit.sim.scenarios._diff_astar_sites import (
    HOUSE_ROOMS,
    INFLATION,
    Site,
    SiteName,
    heading_of,
    resolve_building,
    site,
)

__all__ = ["DiffAStar"]

#: The nominal drive: 0.3 m track, 0.05 m wheels.
DRIVE = DiffDrive(track=0.3, wheel_radius=0.05)
#: Radius of the round body, m (smaller than the 0.3 m inflation, as on the paper's robot).
BODY_RADIUS = 0.2
TICKS_PER_REV = 4096
ENCODER_BITS = 16
PHYSICS_RATE = 100.0  # Hz
CONTROL_RATE = 20.0  # Hz
#: Noise of a noisy trial: wheel slip scale, wheel radius error (standard
#: deviation, per wheel and trial), LiDAR beam jitter (rad) and dropout rate.
SLIP = 0.01
RADIUS_ERROR = 0.003
JITTER = math.radians(0.1)
DROPOUT = 0.02
#: A leg is reached when the true position ends this close to its waypoint, m.
GOAL_RADIUS = 0.1
#: Shortest and longest simulated time a trial may be given, s.
MIN_DURATION = 0.1
MAX_DURATION = 3600.0
#: Plans timed per leg for the planning time (their median is reported).
PLAN_REPEATS = 5

Part = Literal["house", "building"]
_PARTS: tuple[Part, ...] = ("house", "building")
_BUILDINGS = ("auto", "willow", "corridor")

#: The paper's figures as printed: planning time (ms), path length (m), travel
#: time (s), cross-track MAE and max (cm); house legs, the house's two legs
#: together, the building route. None where the paper gives none. Text, so that
#: the table shows them exactly as published.
PAPER: dict[str, tuple[str | None, str | None, str | None, str | None, str | None]] = {
    "house leg 1": ("21.6", "7.925", "59.98", None, None),
    "house leg 2": ("22.2", "5.663", "40.08", None, None),
    "house, both legs": (None, None, None, "2.9", "8.3"),
    "building": ("423", None, "170.2", "1.7", "7.3"),
}


class _Mission:
    """Simulation controller: FollowTheCarrot on the localiser's pose, leg after leg."""

    def __init__(self, tracker: FollowTheCarrot, routes: Sequence[Path2D]) -> None:
        self.tracker = tracker
        self.follow = TrackerController(tracker, control_rate=CONTROL_RATE)
        self.routes = tuple(routes)
        self.leg = 0
        #: Simulated time at which each leg's tracker reported arrival, s.
        self.ends: list[float] = []
        tracker.set_path(self.routes[0])

    @property
    def done(self) -> bool:
        return self.leg >= len(self.routes)

    def __call__(self, obs: Observation) -> Twist2D:
        if self.tracker.done:
            self.leg += 1
            if self.done:
                return Twist2D(0.0, 0.0, 0.0)
            self.tracker.set_path(self.routes[self.leg])
        twist = self.follow(obs)
        if self.tracker.done:
            self.ends.append(obs.t)
        return twist


def _robot(noise: bool, rng: np.random.Generator) -> Robot:
    """The delivery robot, with its wheel imperfections drawn from ``rng`` when noisy."""
    encoders = WheelEncoders(ticks_per_rev=TICKS_PER_REV, bits=ENCODER_BITS, rate=50.0)
    if not noise:
        return Robot(drive=DRIVE, footprint=BODY_RADIUS, max_wheel_speed=10.0,
                     max_wheel_acceleration=20.0, encoders=encoders,
                     lidar=Lidar(noise=None))  # fmt: skip
    error = np.clip(rng.normal(0.0, RADIUS_ERROR, 2), -0.05, 0.05)
    return Robot(drive=DRIVE, footprint=BODY_RADIUS, max_wheel_speed=10.0,
                 max_wheel_acceleration=20.0, wheel_slip=SLIP, wheel_radius_error=error,
                 encoders=encoders, lidar=Lidar(angle_jitter=JITTER, dropout=DROPOUT))  # fmt: skip


def _cross_track(route: Path2D, points_xy: np.ndarray) -> np.ndarray:
    """Distance of each point (NaN rows dropped) to the route, m."""
    pts = points_xy[~np.isnan(points_xy).any(axis=1)]
    if pts.shape[0] == 0:
        return np.zeros(0)
    line = (
        shapely.LineString(route.points)
        if len(route.points) > 1
        else shapely.Point(route.points[0])
    )
    return np.asarray(shapely.distance(line, shapely.points(pts)), dtype=np.float64)


def _stat(values: np.ndarray, fn: Literal["mean", "max"]) -> float:
    if values.size == 0:
        return math.nan
    return float(values.mean() if fn == "mean" else values.max())


def _leg_values(
    place: Site, trace: Trace, ends: Sequence[float]
) -> tuple[dict[str, float], list[np.ndarray], list[np.ndarray]]:
    """Per-leg figures of a run, and each leg's cross-track samples (true, estimated)."""
    values: dict[str, float] = {}
    true_xte: list[np.ndarray] = []
    est_xte: list[np.ndarray] = []
    times = trace.times
    t_end_run = float(times[-1])
    begin = 0.0
    for k, route in enumerate(place.routes):
        leg = f"leg{k + 1}_"
        # A leg starts when the one before it finishes: a run cut short never
        # drives the legs after the unfinished one, so they have no samples
        # (its last pose is not on their routes).
        started = k <= len(ends)
        finished = k < len(ends)
        end = ends[k] if finished else t_end_run
        rows = (times >= begin - 1e-9) & (times <= end + 1e-9)
        if not started or not rows.any():
            xt = xe = np.zeros(0)
            final_error = math.nan
        else:
            xt = _cross_track(route, trace.poses[rows, :2])
            xe = _cross_track(route, trace.estimates[rows, :2])
            last = trace.poses[np.flatnonzero(rows)[-1], :2]
            goal = place.waypoints[k + 1]
            final_error = math.hypot(float(last[0] - goal[0]), float(last[1] - goal[1]))
        true_xte.append(xt)
        est_xte.append(xe)
        values[leg + "path_length"] = route.length
        values[leg + "expanded"] = float(route.expanded)
        values[leg + "travel_time"] = end - begin if finished else math.nan
        values[leg + "xte_mean"] = _stat(xt, "mean")
        values[leg + "xte_max"] = _stat(xt, "max")
        values[leg + "xte_est_mean"] = _stat(xe, "mean")
        values[leg + "xte_est_max"] = _stat(xe, "max")
        values[leg + "final_error"] = final_error
        values[leg + "reached"] = float(finished and final_error <= GOAL_RADIUS)
        begin = end
    return values, true_xte, est_xte


def _planning_times(name: SiteName, data_dir: str | None) -> tuple[float, tuple[float, ...]]:
    """Costmap build time and each leg's A* time (median of warm runs), s."""
    place = site(name, data_dir)
    t0 = time.perf_counter()
    MapPlanner(place.grid, robot_radius=INFLATION)
    build = time.perf_counter() - t0
    legs = []
    for a, b in itertools.pairwise(place.waypoints):
        place.planner.plan(a, b)  # warm: compiled kernels loaded
        runs = []
        for _ in range(PLAN_REPEATS):
            t0 = time.perf_counter()
            place.planner.plan(a, b)
            runs.append(time.perf_counter() - t0)
        legs.append(statistics.median(runs))
    return build, tuple(legs)


def _agg(
    results: Sequence[TrialResult], key: str, how: Literal["mean", "max", "min", "sum"]
) -> float:
    """A value over trials (NaNs ignored; NaN when none has it)."""
    vals = np.array([r.values.get(key, math.nan) for r in results], dtype=np.float64)
    vals = vals[~np.isnan(vals)]
    if vals.size == 0:
        return math.nan
    if how == "mean":
        return float(vals.mean())
    if how == "max":
        return float(vals.max())
    if how == "min":
        return float(vals.min())
    return float(vals.sum())


def _ms(seconds: float) -> float:
    return seconds * 1e3


def _cm(metres: float) -> float:
    return metres * 1e2


class DiffAStar(Scenario):
    """The differential delivery robot: A* + follow-the-carrot in a house, then a building.

    **House.** A differential robot (0.3 m track, 0.05 m wheels, a round body
    of 0.2 m radius) starts at (−1, −4) m and visits (−4, 0) and then
    (−4, −2) m in a house of three rooms built from a floor plan (see
    :data:`~navkit.sim.scenarios._diff_astar_sites.HOUSE_ROOMS`: a 3.5 × 8 m
    living room with a kitchen counter, a 3.5 × 3 m bedroom and a 3.5 × 5 m
    study, 0.9 m doors). Each leg is planned by A* on the map inflated by
    0.3 m (:class:`~navkit.planning.MapPlanner`) and tracked by
    :class:`~navkit.control.FollowTheCarrot` at 0.18 m/s (the paper's
    settings, its defaults).

    **Building.** One route (0, 0) → (32, 6) m at 0.25 m/s. The paper's
    buildings are not published: on the Willow Garage office map (real data,
    ``ros-map-server-maps/willow_garage_2010``) the route runs from its point
    (19.05, 38.55) m to (51.05, 44.55) m, reported translated so the start is
    (0, 0); without the data (or with ``building="corridor"``) in a
    procedurally built corridor building from (0, 0) to (32, 6) m.

    The robot tracks its *estimated* pose: wheel odometry corrected at each
    scan of a 360-beam, 10 Hz LiDAR by scan-to-map matching (a stand-in for
    the paper's AMCL). Noisy trials (the default) draw wheel slip, wheel
    radius errors, LiDAR range noise, beam jitter and dropouts from their
    seed. Cross-track errors are measured on the true pose against the A*
    route; the table puts planning time, path length, travel time and
    cross-track MAE and maximum beside the paper's.

    Every option is keyword-only.

    Parameters
    ----------
    parts : sequence of {"house", "building"}, default ("house", "building")
        What to run, in this order (one case each).
    building : {"auto", "willow", "corridor"}, default "auto"
        The building route's map: the Willow Garage map, the corridor
        building, or the map when found and the corridor building otherwise.
    noise : bool, default True
        Sensor and wheel noise; without it every trial of a case is the same.
    data_dir : str or path-like, optional
        The data folder holding ``ros-map-server-maps`` (see
        :func:`~navkit.sim.scenarios.find_data`).
    duration : float or None, default None
        Longest simulated time of a trial, s, in [0.1, 3600]; None: three times
        the time the route takes at the paper's speed, plus a minute. A trial
        cut short has NaN travel times for the legs it did not finish.

    Raises
    ------
    TypeError
        ``parts`` not a sequence of str, ``building`` not a str, ``noise`` not
        a bool, ``data_dir`` not a path or None, ``duration`` not a real number.
    ValueError
        ``parts`` not 'house' and/or 'building' once each, an unknown
        ``building``, ``duration`` outside its range.

    Examples
    --------
    >>> scenario = DiffAStar(parts=("house",))
    >>> scenario.cases(3)
    (('house: (-1, -4) -> (-4, 0) -> (-4, -2) m at 0.18 m/s', 3),)
    """

    name = "diff-astar"
    title = "differential delivery robot: A* + follow-the-carrot, three-room house and 32 m route"
    paper = (
        "Differential-drive delivery robot: A* on a map inflated by 0.3 m and "
        "follow-the-carrot tracking (0.18 m/s in a three-room house, 0.25 m/s on a "
        "32 m building route)"
    )
    default_trials = 10

    def __init__(
        self,
        *,
        parts: Sequence[Part] = _PARTS,
        building: Literal["auto", "willow", "corridor"] = "auto",
        noise: bool = True,
        data_dir: str | os.PathLike[str] | None = None,
        duration: float | None = None,
    ) -> None:
        if isinstance(parts, str) or not isinstance(parts, Sequence):
            raise TypeError(f"parts must be a sequence of part names, got {type(parts).__name__}")
        names = tuple(parts)
        for k, name in enumerate(names):
            if not isinstance(name, str):  # before the set below: a list does not hash
                raise TypeError(f"parts[{k}] must be a str, got {type(name).__name__}")
        # Checked and kept as plain str (an np.str_ printed as np.str_(...) in the repr).
        names = tuple(cast(Part, as_text(name, "parts")) for name in names)
        if not names or len(set(names)) != len(names) or any(p not in _PARTS for p in names):
            raise ValueError(f"parts must hold 'house' and/or 'building' once each, got {names!r}")
        if not isinstance(building, str):
            raise TypeError(f"building must be a str, got {type(building).__name__}")
        building = cast(Literal["auto", "willow", "corridor"], as_text(building, "building"))
        if building not in _BUILDINGS:
            raise ValueError(f"building must be one of {list(_BUILDINGS)}, got {building!r}")
        if data_dir is not None and not isinstance(data_dir, (str, os.PathLike)):
            raise TypeError(f"data_dir must be a path or None, got {type(data_dir).__name__}")
        self.parts: tuple[Part, ...] = names
        self.building: Literal["auto", "willow", "corridor"] = building
        self.noise: bool = as_bool(noise, "noise")
        self.data_dir: str | None = None if data_dir is None else os.fspath(data_dir)
        # The building and its data folder, resolved now (as Demo's map) so that
        # every worker of a sweep runs the same building.
        self._building, self._site_dir = resolve_building(building, self.data_dir)
        self.duration: float | None = None
        if duration is not None:
            limit = positive_float(duration, "duration")
            if not MIN_DURATION <= limit <= MAX_DURATION:
                raise ValueError(
                    f"duration must lie in [{MIN_DURATION:g}, {MAX_DURATION:g}] s, got {limit}"
                )
            self.duration = limit

    def __repr__(self) -> str:
        return (
            f"DiffAStar(parts={self.parts!r}, building={self.building!r}, noise={self.noise}, "
            f"data_dir={self.data_dir!r}, duration={self.duration!r})"
        )

    def _site_name(self, part: Part) -> SiteName:
        return "house" if part == "house" else self._building

    def _label(self, part: Part) -> str:
        if part == "house":
            return "house: (-1, -4) -> (-4, 0) -> (-4, -2) m at 0.18 m/s"
        where = "Willow Garage map" if self._site_name(part) == "willow" else "corridor building"
        return f"building ({where}): (0, 0) -> (32, 6) m at 0.25 m/s"

    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        """One case per part; without noise each runs once.

        Parameters
        ----------
        trials : int
            Trials per case (>= 1).

        Returns
        -------
        tuple of (str, int)
            ``(description, trials)`` per part.

        Examples
        --------
        >>> for case in DiffAStar(building="corridor").cases(3):
        ...     print(case)
        ('house: (-1, -4) -> (-4, 0) -> (-4, -2) m at 0.18 m/s', 3)
        ('building (corridor building): (0, 0) -> (32, 6) m at 0.25 m/s', 3)
        >>> [count for _, count in DiffAStar(building="corridor", noise=False).cases(3)]
        [1, 1]
        """
        count = self._check_trials(trials) if self.noise else 1
        return tuple((self._label(part), count) for part in self.parts)

    def run_trial(self, trial: Trial) -> TrialResult:
        """Plan and drive one part's route (all its legs in one run).

        Parameters
        ----------
        trial : Trial
            Which part (``case_index``) and seed.

        Returns
        -------
        TrialResult
            Per-leg values (``leg1_travel_time``, ``leg1_xte_max``, ...), the
            run's (``xte_max``, ``collisions``, ``loc_error_mean``, ...) and
            the trace; SI units (lengths and errors in m, times in s), flags
            as 0.0/1.0, NaN for what a trial cut short did not reach.

        Raises
        ------
        DataNotFoundError
            ``building="willow"`` without the Willow Garage map.

        Examples
        --------
        >>> scenario = DiffAStar(parts=("house",), building="corridor", noise=False,
        ...                      duration=0.5)  # only 0.5 s of the house route
        >>> r = scenario.run_trial(scenario.trials(1)[0])
        >>> round(r.values["leg1_path_length"], 2), r.values["sim_time"], r.values["collisions"]
        (7.97, 0.5, 0.0)
        >>> r.values["leg1_reached"], math.isnan(r.values["leg1_travel_time"])  # cut short
        (0.0, True)
        """
        t_wall = time.perf_counter()
        part = self.parts[self._case_of(trial)]
        place = site(self._site_name(part), self._site_dir)
        robot_rng, sim_rng = (
            np.random.default_rng(s) for s in np.random.SeedSequence(trial.seed).spawn(2)
        )
        robot = _robot(self.noise, robot_rng)
        assert robot.lidar is not None
        start = Pose2D(float(place.waypoints[0, 0]), float(place.waypoints[0, 1]),
                       heading_of(place.routes[0]))  # fmt: skip
        mission = _Mission(FollowTheCarrot(max_speed=place.speed), place.routes)
        localizer = ScanLocalizer(place.field, DRIVE, robot.lidar, ticks_per_rev=TICKS_PER_REV,
                                  bits=ENCODER_BITS, start=start)  # fmt: skip
        reference = np.concatenate([r.points for r in place.routes])
        length = float(sum(r.length for r in place.routes))
        trace = Simulation(
            place.world, robot, mission, start=start, goal=place.waypoints[-1],
            goal_tolerance=GOAL_RADIUS, reference_path=reference, estimator=localizer,
            rate=PHYSICS_RATE, control_rate=CONTROL_RATE,
            duration=self.duration or 3.0 * length / place.speed + 60.0,
            seed=sim_rng, stop_at_goal=False, wall_timeout=600.0,
        ).run()  # fmt: skip
        values, true_xte, est_xte = _leg_values(place, trace, mission.ends)
        m = trace.metrics
        xt = np.concatenate(true_xte)
        xe = np.concatenate(est_xte)
        est_ok = ~np.isnan(trace.estimates).any(axis=1)
        loc = np.hypot(*(trace.estimates[est_ok, :2] - trace.poses[est_ok, :2]).T)
        legs = len(place.routes)
        values.update(
            reached=float(all(values[f"leg{k + 1}_reached"] == 1.0 for k in range(legs))
                          and m.collisions == 0),
            collisions=float(m.collisions),
            min_clearance=m.min_clearance,
            xte_mean=_stat(xt, "mean"),
            xte_max=_stat(xt, "max"),
            xte_est_mean=_stat(xe, "mean"),
            xte_est_max=_stat(xe, "max"),
            loc_error_mean=_stat(loc, "mean"),
            loc_error_max=_stat(loc, "max"),
            sim_time=m.duration,
            scans_matched=float(localizer.matches),
        )  # fmt: skip
        return TrialResult(trial, values, trace, time.perf_counter() - t_wall)

    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
        """Tables beside the paper's, the headline summary and the house's scene.

        Planning times are measured here, in this process (median of
        :data:`PLAN_REPEATS` warm A* runs per leg): they are machine figures,
        so they go into the table but not into ``summary``, which stays the
        same for a seed.

        Parameters
        ----------
        results : sequence of TrialResult
            Every trial, in order.
        seed : int
            The base seed.

        Returns
        -------
        ScenarioResult
            Two tables (navkit beside the paper; reach, collisions and
            localisation), the summary (SI units: m, s; rates in [0, 1]) and a
            scene.

        Examples
        --------
        >>> scenario = DiffAStar(parts=("house",), building="corridor", noise=False,
        ...                      duration=0.5)
        >>> result = scenario.summarize([scenario.run_trial(scenario.trials(1)[0])], seed=0)
        >>> len(result.tables), round(result.summary["house_leg1_path_length"], 2)  # m
        (2, 7.97)
        >>> assert result.scene is not None  # the scenario draws one
        >>> result.summary["house_reached_rate"], result.scene.title[:17]
        (0.0, 'diff-astar: house')
        """
        results, by_case, seed = self._results_by_case(results, seed)
        rows: list[tuple[Any, ...]] = []
        robust: list[tuple[Any, ...]] = []
        summary: dict[str, float] = {}
        notes: list[str] = []
        scene: Scene | None = None
        for ci, part in enumerate(self.parts):
            got = by_case.get(ci, [])
            if not got:
                continue
            name = self._site_name(part)
            place = site(name, self._site_dir)
            build, plan = _planning_times(name, self._site_dir)
            n = len(got)
            if part == "house":
                for k in range(len(place.routes)):
                    leg = f"leg{k + 1}_"
                    paper = PAPER[f"house leg {k + 1}"]
                    rows.append((
                        f"house leg {k + 1}", _ms(plan[k]), paper[0],
                        _agg(got, leg + "path_length", "mean"), paper[1],
                        _agg(got, leg + "travel_time", "mean"), paper[2],
                        _cm(_agg(got, leg + "xte_mean", "mean")), None,
                        _cm(_agg(got, leg + "xte_max", "max")), None,
                    ))  # fmt: skip
                    summary[f"house_{leg}path_length"] = _agg(got, leg + "path_length", "mean")
                    summary[f"house_{leg}travel_time"] = _agg(got, leg + "travel_time", "mean")
                    summary[f"house_{leg}xte_max"] = _agg(got, leg + "xte_max", "max")
                paper = PAPER["house, both legs"]
                rows.append((
                    "house, both legs", _ms(sum(plan)), None,
                    float(sum(r.length for r in place.routes)), None,
                    _agg(got, "leg1_travel_time", "mean") + _agg(got, "leg2_travel_time", "mean"),
                    None, _cm(_agg(got, "xte_mean", "mean")), paper[3],
                    _cm(_agg(got, "xte_max", "max")), paper[4],
                ))  # fmt: skip
                label = "house"
            else:
                paper = PAPER["building"]
                rows.append((
                    "building", _ms(plan[0]), paper[0],
                    _agg(got, "leg1_path_length", "mean"), paper[1],
                    _agg(got, "leg1_travel_time", "mean"), paper[2],
                    _cm(_agg(got, "xte_mean", "mean")), paper[3],
                    _cm(_agg(got, "xte_max", "max")), paper[4],
                ))  # fmt: skip
                summary["building_path_length"] = _agg(got, "leg1_path_length", "mean")
                summary["building_travel_time"] = _agg(got, "leg1_travel_time", "mean")
                label = "building"
            # Wall clock, so in a "wall" column of a row of its own, not in the notes:
            # the notes, like every figure but the wall ones, repeat for a seed.
            rows.append((f"{label} costmap (built once)", _ms(build), *(None,) * 9))
            summary[f"{label}_xte_mean"] = _agg(got, "xte_mean", "mean")
            summary[f"{label}_xte_max"] = _agg(got, "xte_max", "max")
            summary[f"{label}_reached_rate"] = _agg(got, "reached", "mean")
            summary[f"{label}_collisions"] = _agg(got, "collisions", "sum")
            summary[f"{label}_min_clearance"] = _agg(got, "min_clearance", "min")
            summary[f"{label}_loc_error_mean"] = _agg(got, "loc_error_mean", "mean")
            summary[f"{label}_loc_error_max"] = _agg(got, "loc_error_max", "max")
            robust.append((
                label, n, _agg(got, "reached", "sum"), _agg(got, "collisions", "sum"),
                _cm(_agg(got, "min_clearance", "min")),
                _cm(_agg(got, "loc_error_mean", "mean")), _cm(_agg(got, "loc_error_max", "max")),
                _cm(_agg(got, "xte_est_mean", "mean")), _cm(_agg(got, "xte_est_max", "max")),
            ))  # fmt: skip
            notes.extend(_site_notes(part, name, place))
            if scene is None:
                scene = _scene(place, label, got[0])
        notes.extend(_common_notes(self.noise))
        main = Table(
            "diff-astar: A* (0.3 m inflation) + FollowTheCarrot, navkit beside the paper "
            "(means over trials; max = largest over trials)",
            ("route", "planning (wall ms)", "paper", "length (m)", "paper", "travel (s)", "paper",
             "cross-track MAE (cm)", "paper", "cross-track max (cm)", "paper"),
            tuple(rows), tuple(notes),
        )  # fmt: skip
        second = Table(
            "diff-astar: reach, collisions and localisation (true pose vs the localiser's)",
            ("part", "trials", "reached", "collisions", "min clearance (cm)",
             "loc. error mean (cm)", "loc. error max (cm)", "estimate's cross-track MAE (cm)",
             "estimate's cross-track max (cm)"),
            tuple(robust),
            ("The paper's cross-track errors are presumably measured on its localisation "
             "(AMCL) pose; the estimate's columns are that view, the main table's the "
             "true pose.",),
        )  # fmt: skip
        return ScenarioResult(
            scenario=self.name, seed=seed, trials=tuple(results), tables=(main, second),
            summary=summary, scene=scene,
        )  # fmt: skip


def _site_notes(part: Part, name: str, place: Site) -> list[str]:
    costmap = "(its 0.3 m-inflated costmap is built once: the costmap row)"
    if part == "house":
        rooms = "; ".join(
            f"{room} x {b[0]:g}..{b[2]:g}, y {b[1]:g}..{b[3]:g} m ({extra})"
            for room, b, extra in HOUSE_ROOMS
        )
        return [
            f"House (built from a floor plan; 0.1 m walls, 0.05 m map {costmap}): {rooms}.",
        ]
    if name == "willow":
        sx, sy = place.waypoints[0]
        gx, gy = place.waypoints[-1]
        return [
            "Building: the Willow Garage office map (willow-2010-02-18-0.10, 0.1 m cells) "
            f"{costmap}, from its point ({sx:g}, {sy:g}) m to ({gx:g}, {gy:g}) m, i.e. "
            "(0, 0) -> (32, 6) m in the table (the paper's buildings are not published).",
        ]
    return [
        "Building: a procedurally built corridor building (the Willow Garage map was not "
        "found): a 2 m corridor along y = 0 with 4 m offices on both sides and a side "
        f"corridor north along x = 32 m, 0.05 m map {costmap}.",
    ]


def _common_notes(noise: bool) -> list[str]:
    noisy = (
        "Noise per trial (seeded): wheel slip 1 % (per step), wheel radius errors 0.3 % "
        "(per wheel), LiDAR range noise 2.23 % below 3 m and 5.38 % beyond, 0.1 deg beam "
        "jitter, 2 % dropouts."
        if noise
        else "Noise-free run: exact wheels and LiDAR."
    )
    return [
        "Robot: differential drive, 0.3 m track, 0.05 m wheels (at most 20 rad/s^2), round "
        "body of 0.2 m radius; 4096-tick encoders at 50 Hz; a 360-beam, 10 Hz, 12 m LiDAR. "
        "It tracks its estimated pose (wheel odometry corrected by scan-to-map matching at "
        "each scan, standing in for the paper's AMCL), control 20 Hz, physics 100 Hz; it "
        "starts facing its route.",
        noisy,
        "Planning time: navkit's compiled A* (8-connected, on the inflated costmap), median "
        "of 5 warm runs on this machine (wall clock, as the costmap rows' time to build the "
        "costmap); the paper's times are its own stack's.",
        "Travel time: from the start of the leg to FollowTheCarrot's arrival (0.05 m on the "
        "estimate). The paper's robot averaged 0.13 m/s in the house (7.925 m in 59.98 s) "
        "against its 0.18 m/s; its acceleration limits and turns in place are not "
        "published. Cross-track: distance of the true position to the A* route at every "
        "physics step.",
    ]


def _scene(place: Site, label: str, first: TrialResult) -> Scene:
    paths = tuple((f"{label} leg {k + 1} (A*)", r.points) for k, r in enumerate(place.routes))
    traces = (("trial 0", first.trace),) if first.trace is not None else ()
    return Scene(
        title=f"diff-astar: {label}, A* + FollowTheCarrot (world coordinates of the map)",
        grid=place.grid,
        world=None if place.name == "willow" else place.world,
        paths=paths,
        traces=traces,
        points=(("start", place.waypoints[:1]), ("waypoints", place.waypoints[1:])),
    )
