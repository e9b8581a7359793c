"""omni-apf: the omnidirectional LiDAR robot's potential-field runs to four targets."""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from typing import Any

import numpy as np
import shapely

from navkit._shared.validation import as_bool, as_float_array, positive_float
from navkit.estimation import OmniOdometry
from navkit.sim import (
    Scenario,
    ScenarioResult,
    Scene,
    Simulation,
    Table,
    Trace,
    Trial,
    TrialResult,
)
from navkit.sim.scenarios._omni_apf_setup import (
    ARRIVE_TOLERANCE,
    BODY_RADIUS,
    DRIVE,
    ApfController,
    obstacle_boxes,
    omni_robot,
    omni_world,
)

__all__ = ["PAPER_TARGETS", "OmniApf"]

#: The paper's targets, m, all from the origin.
PAPER_TARGETS: tuple[tuple[float, float], ...] = ((0.0, 3.0), (0.0, -3.0), (3.0, 0.0), (-3.0, 0.0))
#: The paper's figures: every final error under 40 mm; mean times per target
#: from 11.2 to 12.9 s.
PAPER_ERROR_MM = 40.0
PAPER_TIME_RANGE_S = (11.2, 12.9)
CONTROL_RATE = 20.0  # Hz
PHYSICS_RATE = 100.0  # Hz
_MAX_TARGET = 50.0  # m
#: Shortest route with the obstacle on it, m. On a route under 3 m the box stands
#: halfway; from 1 m on it stays 0.13 m or more clear of the robot's body both at
#: the start and at the target (at 0.7 m it overlaps the body at the start).
_MIN_OBSTACLE_ROUTE = 1.0  # m
_MIN_DURATION = 0.1  # s
_MAX_DURATION = 3600.0  # s
#: The values of a trial (what run_trial gives and summarize reads).
_KEYS = ("target_x", "target_y", "final_x", "final_y", "odometry_x", "odometry_y", "error",
         "odometry_error", "drift", "time", "reached", "collisions", "min_clearance",
         "distance")  # fmt: skip


def _targets(value: Any) -> tuple[tuple[float, float], ...]:
    # The messages show values by repr: with :g, 50.0000001 m reads "50 m", in range.
    if isinstance(value, (list, tuple)) and not value:
        # Read as shape (0,), which the shape check would report instead of the count.
        raise ValueError("targets must hold 1 to 64 (x, y) pairs, got 0")
    arr = as_float_array(value, "targets", shape=(None, 2))
    if not 1 <= arr.shape[0] <= 64:
        raise ValueError(f"targets must hold 1 to 64 (x, y) pairs, got {arr.shape[0]}")
    dist = np.hypot(arr[:, 0], arr[:, 1])
    bad = np.flatnonzero((dist < 0.5) | (dist > _MAX_TARGET))
    if bad.size:
        k = int(bad[0])
        raise ValueError(
            f"targets[{k}] must lie 0.5 to {_MAX_TARGET:g} m from the start (0, 0), "
            f"got ({float(arr[k, 0])!r}, {float(arr[k, 1])!r}), {float(dist[k])!r} m away"
        )
    return tuple((float(x), float(y)) for x, y in arr)


def _check_obstacle_routes(targets: tuple[tuple[float, float], ...]) -> None:
    """Every route long enough for the obstacle box to stand clear of both of its ends.

    The boxes of all routes stand in the one world: the robot's body at each
    target must also clear the boxes on the other routes.
    """
    for k, (x, y) in enumerate(targets):
        dist = math.hypot(x, y)
        if dist < _MIN_OBSTACLE_ROUTE:
            raise ValueError(
                f"targets[{k}] must lie at least {_MIN_OBSTACLE_ROUTE:g} m from the start "
                f"when the obstacle series runs (obstacles None or True): the box on a "
                f"shorter route touches the robot at its start or at the target; got "
                f"({x!r}, {y!r}), {dist!r} m away"
            )
    boxes = obstacle_boxes(targets)
    for k, (x, y) in enumerate(targets):
        for j, obstacle in enumerate(boxes):
            gap = shapely.distance(obstacle, shapely.Point(x, y))
            if j != k and gap <= BODY_RADIUS:
                raise ValueError(
                    f"targets[{k}] ({x:g}, {y:g}) lies {gap:g} m from the obstacle box on the "
                    f"route to targets[{j}], within the robot's radius of {BODY_RADIUS:g} m: "
                    "the robot cannot stand there when the obstacle series runs "
                    "(obstacles None or True)"
                )


class OmniApf(Scenario):
    """The omnidirectional LiDAR robot: compass-fused odometry and a piecewise potential field.

    A three-wheel omni robot (wheels at 30°, 150° and 270°, 5 cm wheels 0.2 m
    from the centre, a round body of 0.22 m radius) drives from (0, 0) to each
    target — the paper's (0, 3), (0, -3), (3, 0) and (-3, 0) m — on its
    compass-fused wheel odometry (:class:`~navkit.estimation.OmniOdometry`:
    wheel displacements rotated by the compass heading). Its velocity is the
    paper's field: piecewise-linear attraction toward the target plus the
    piecewise repulsion of every LiDAR beam
    (:func:`~navkit.planning.piecewise_repulsive_force_from_scan`), clipped to
    0.35 m/s and rate-limited (:func:`~navkit.control.limit_velocity_change`);
    the heading is held at 0. It stops when the odometry is within 15 mm of the
    target. The route is run without and with an obstacle on the way (a 0.3 m
    box 1.5 m along it, its centre 0.2 m beside the line), in a 9 × 9 m room.

    Noisy trials use the paper's RPLIDAR range errors
    (:class:`~navkit.sim.RangeNoise`'s default: 2.23 % / 5.38 %), a compass
    with 1° noise and a little random wheel slip (0.005), so the odometry
    drifts from the truth; the paper's measured latencies (0.50 s for the
    LiDAR, 0.08 s for odometry: the encoders and the compass) apply unless
    ``latency=False``. With ``noise=False`` every trial of a case is the same,
    so each case runs once.

    Every option is keyword-only.

    Parameters
    ----------
    noise : bool, default True
        Sensor noise and wheel slip.
    latency : bool, default True
        The paper's measured sensor latencies.
    obstacles : bool or None, default None
        None: both of the paper's series (without, then with the obstacle);
        True or False: only that one.
    targets : sequence of (x, y), default the paper's four
        Targets in m, each 0.5 to 50 m from the start (at most 64); with the
        obstacle series (``obstacles`` None or True) at least 1 m, so that the
        box stands clear of the robot at both ends of its route, and none
        where the robot would touch the box on another target's route.
    duration : float, default 40.0
        Longest simulated time of a trial, s, in [0.1, 3600].

    Raises
    ------
    TypeError
        ``noise``, ``latency`` or ``obstacles`` not a bool (``obstacles`` also
        None), ``targets`` or ``duration`` not real numbers.
    ValueError
        ``duration`` or the number of ``targets`` outside its range, a target
        nearer than 0.5 m to the start or too far from it, or (with the
        obstacle series) too near the start or an obstacle box, naming it.

    Examples
    --------
    >>> scenario = OmniApf(noise=False, obstacles=False, targets=[(0.0, 1.0)], duration=10.0)
    >>> [trial.case for trial in scenario.trials(5)]
    ['target (0, 1) m, no obstacle']
    >>> result = scenario.run_trial(scenario.trials()[0])
    >>> result.values["reached"], result.values["error"] < 0.04
    (1.0, True)
    """

    name = "omni-apf"
    title = "3-wheel omni robot: compass-fused odometry, piecewise potential field on LiDAR beams"
    paper = (
        "Omnidirectional robot with LiDAR: compass-fused odometry and a piecewise artificial "
        "potential field (targets at 3 m; errors < 40 mm, mean times 11.2-12.9 s)"
    )
    default_trials = 5

    def __init__(
        self,
        *,
        noise: bool = True,
        latency: bool = True,
        obstacles: bool | None = None,
        targets: Sequence[Sequence[float]] = PAPER_TARGETS,
        duration: float = 40.0,
    ) -> None:
        self.noise: bool = as_bool(noise, "noise")
        self.latency: bool = as_bool(latency, "latency")
        self.obstacles: bool | None = None if obstacles is None else as_bool(obstacles, "obstacles")
        self.targets: tuple[tuple[float, float], ...] = _targets(targets)
        if self.obstacles is not False:
            _check_obstacle_routes(self.targets)
        self.duration: float = positive_float(duration, "duration")
        if not _MIN_DURATION <= self.duration <= _MAX_DURATION:
            raise ValueError(
                f"duration must lie in [{_MIN_DURATION:g}, {_MAX_DURATION:g}] s, "
                f"got {self.duration}"
            )

    def __repr__(self) -> str:
        return (
            f"OmniApf(noise={self.noise}, latency={self.latency}, obstacles={self.obstacles}, "
            f"targets={self.targets}, duration={self.duration})"
        )

    def _series(self) -> tuple[bool, ...]:
        return (False, True) if self.obstacles is None else (self.obstacles,)

    def _case(self, index: int) -> tuple[tuple[float, float], bool]:
        """The target and obstacle flag of a (checked) case index."""
        n = len(self.targets)
        return self.targets[index % n], self._series()[index // n]

    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        """The targets, first without then with the obstacle.

        Parameters
        ----------
        trials : int
            Trials per case (>= 1); a noise-free run has one per case.

        Returns
        -------
        tuple of (str, int)
            ``("target (0, 3) m, obstacle", trials)`` and so on.

        Examples
        --------
        >>> OmniApf(targets=[(3.0, 0.0)]).cases(5)
        (('target (3, 0) m, no obstacle', 5), ('target (3, 0) m, obstacle', 5))
        """
        trials = self._check_trials(trials)
        count = int(trials) if self.noise else 1
        return tuple(
            (f"target ({x:g}, {y:g}) m, {'obstacle' if obst else 'no obstacle'}", count)
            for obst in self._series()
            for x, y in self.targets
        )

    def run_trial(self, trial: Trial) -> TrialResult:
        """Drive to the trial's target and measure where the robot stopped.

        Parameters
        ----------
        trial : Trial
            The case (target, obstacle) and the seed of the noise.

        Returns
        -------
        TrialResult
            ``values``: ``target_x``, ``target_y``, ``final_x``, ``final_y`` (true),
            ``odometry_x``, ``odometry_y``, ``error`` (true final position to the
            target, m), ``odometry_error`` (odometry to the target), ``drift``
            (odometry to the true position), ``time`` (when the robot stopped, s;
            NaN if it did not), ``reached`` (1 when it stopped at the target
            without touching anything), ``collisions``, ``min_clearance`` (m) and
            ``distance`` (m driven); and the trace.

        Examples
        --------
        >>> scenario = OmniApf(noise=False, obstacles=False, targets=[(1.0, 0.0)])
        >>> r = scenario.run_trial(scenario.trials()[0])
        >>> round(r.values["final_x"], 2), r.values["collisions"]
        (0.99, 0.0)
        """
        target, obstacle = self._case(self._case_of(trial))
        began = time.perf_counter()
        controller = ApfController(target, control_rate=CONTROL_RATE)
        sim = Simulation(
            omni_world(self.targets, obstacle),
            omni_robot(self.noise, self.latency),
            controller,
            start=(0.0, 0.0, 0.0),
            goal=target,
            goal_tolerance=2.0 * ARRIVE_TOLERANCE,
            estimator=OmniOdometry(DRIVE),
            rate=PHYSICS_RATE,
            control_rate=CONTROL_RATE,
            duration=self.duration,
            seed=trial.seed,
            stop_at_goal=False,
        )
        trace = sim.run()
        return TrialResult(
            trial, _values(trace, target, controller), trace, time.perf_counter() - began
        )

    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
        """The paper's tables: final positions trial by trial, then MAE and times per target.

        Parameters
        ----------
        results : sequence of TrialResult
            Every trial of :meth:`trials`, in order.
        seed : int
            The run's base seed.

        Returns
        -------
        ScenarioResult
            Two tables, the summary (``error_max``, ``error_mean``,
            ``odometry_error_max``, ``drift_max``, ``time_mean_min``,
            ``time_mean_max``, ``reached_rate``, ``collisions``, ``trials``) and
            a scene with the room, the obstacles and one trace per case.

        Examples
        --------
        >>> scenario = OmniApf(noise=False, obstacles=False, targets=[(1.0, 0.0)])
        >>> trials = scenario.trials()
        >>> out = scenario.summarize([scenario.run_trial(t) for t in trials], seed=0)
        >>> out.summary["reached_rate"], out.summary["error_max"] < 0.04
        (1.0, True)
        """
        results, by_case, seed = self._results_by_case(results, seed, keys=lambda _: _KEYS)
        tables = (_trial_table(results), _target_table(self, by_case))
        return ScenarioResult(
            scenario=self.name,
            seed=seed,
            trials=results,
            tables=tables,
            summary=_summary(results, by_case),
            scene=self._scene(by_case),
        )

    def _scene(self, by_case: dict[int, list[TrialResult]]) -> Scene:
        traces: list[tuple[str, Trace]] = []
        for index in sorted(by_case):
            first = by_case[index][0]
            if first.trace is not None:
                traces.append((first.trial.case, first.trace))
        with_obstacle = True in self._series()
        return Scene(
            "omni-apf: piecewise potential field to four targets"
            + (" (with and without obstacles)" if len(self._series()) == 2 else ""),
            world=omni_world(self.targets, with_obstacle),
            traces=tuple(traces),
            points=(
                ("start", np.zeros((1, 2))),
                ("targets", np.array(self.targets, dtype=np.float64)),
            ),
        )


def _values(trace: Trace, target: tuple[float, float], ctl: ApfController) -> dict[str, float]:
    m = trace.metrics
    fx, fy = (float(v) for v in trace.poses[-1, :2])
    ox, oy = (float(v) for v in trace.estimates[-1, :2])
    tx, ty = target
    stopped = bool(ctl.done)
    return {
        "target_x": tx,
        "target_y": ty,
        "final_x": fx,
        "final_y": fy,
        "odometry_x": ox,
        "odometry_y": oy,
        "error": math.hypot(fx - tx, fy - ty),
        "odometry_error": math.hypot(ox - tx, oy - ty),
        "drift": math.hypot(ox - fx, oy - fy),
        "time": float(ctl.arrived_at) if stopped else math.nan,
        "reached": 1.0 if stopped and m.collisions == 0 else 0.0,
        "collisions": float(m.collisions),
        "min_clearance": float(m.min_clearance),
        "distance": float(m.distance),
    }


def _mm(value: float) -> float:
    return 1000.0 * value


def _trial_table(results: Sequence[TrialResult]) -> Table:
    rows = tuple(
        (
            r.trial.case,
            r.trial.index + 1,
            _mm(r.values["final_x"]),
            _mm(r.values["final_y"]),
            _mm(r.values["odometry_x"]),
            _mm(r.values["odometry_y"]),
            _mm(r.values["error"]),
            r.values["time"],
        )
        for r in results
    )
    return Table(
        "Final positions, trial by trial (as the paper's table)",
        ("case", "trial", "true x (mm)", "true y (mm)", "odometry x (mm)", "odometry y (mm)",
         "error (mm)", "time (s)"),
        rows,
        (
            "error: Euclidean distance from the true final position to the target. "
            "The robot stops on its odometry (15 mm tolerance); true and odometry "
            "positions differ by the odometry's drift.",
        ),
    )  # fmt: skip


def _nanmean(values: Sequence[float]) -> float:
    arr = np.asarray(values, dtype=np.float64)
    arr = arr[np.isfinite(arr)]
    return float(arr.mean()) if arr.size else math.nan


def _target_table(scenario: OmniApf, by_case: dict[int, list[TrialResult]]) -> Table:
    rows = []
    for index in sorted(by_case):
        group = by_case[index]
        target, obstacle = scenario._case(index)
        errors = [r.values["error"] for r in group]
        rows.append(
            (
                f"({target[0]:g}, {target[1]:g})",
                "yes" if obstacle else "no",
                f"{int(sum(r.values['reached'] for r in group))}/{len(group)}",
                _mm(_nanmean(errors)),
                _mm(max(errors)),
                _mm(_nanmean([r.values["odometry_error"] for r in group])),
                _nanmean([r.values["time"] for r in group]),
                f"< {PAPER_ERROR_MM:g}",
                f"{PAPER_TIME_RANGE_S[0]:g}-{PAPER_TIME_RANGE_S[1]:g}",
            )
        )
    noise = "with sensor noise" if scenario.noise else "noise-free"
    latency = "the paper's latencies" if scenario.latency else "no latency"
    return Table(
        f"MAE and mean time per target ({noise}, {latency}) beside the paper",
        ("target (m)", "obstacle", "reached", "MAE (mm)", "max error (mm)",
         "odometry MAE (mm)", "mean time (s)", "paper error (mm)", "paper mean time (s)"),
        tuple(rows),
        (
            "MAE: mean over the trials of the Euclidean error of the true final position; "
            "odometry MAE: the same for the odometry's final position.",
            "The paper reports every error under 40 mm and mean times of 11.2-12.9 s "
            "over its targets; it does not publish its field gains, robot size or obstacle, "
            "so these are navkit's choices (see navkit.sim.scenarios.OmniApf).",
            "With the obstacle navkit's robot brakes in front of it (the piecewise repulsion "
            "of every beam on its face opposes the attraction; the LiDAR's 0.5 s latency "
            "makes it react late) and slides around: slower than the paper's runs.",
        ),
    )  # fmt: skip


def _summary(
    results: Sequence[TrialResult], by_case: dict[int, list[TrialResult]]
) -> dict[str, float]:
    if not results:
        return {"trials": 0.0}
    col = {k: np.array([r.values[k] for r in results], dtype=np.float64)
           for k in ("error", "odometry_error", "drift", "reached", "collisions")}  # fmt: skip
    means = [_nanmean([r.values["time"] for r in group]) for group in by_case.values()]
    finite = [t for t in means if math.isfinite(t)]
    return {
        "error_max": float(col["error"].max()),
        "error_mean": float(col["error"].mean()),
        "odometry_error_max": float(col["odometry_error"].max()),
        "drift_max": float(col["drift"].max()),
        "time_mean_min": min(finite) if finite else math.nan,
        "time_mean_max": max(finite) if finite else math.nan,
        "reached_rate": float(col["reached"].mean()),
        "collisions": float(col["collisions"].sum()),
        "trials": float(len(results)),
    }
