"""``navkit demo``: plan, track and estimate on a real office map in a few seconds."""

from __future__ import annotations

import itertools
import math
import os
from collections.abc import Sequence
from typing import Literal, cast

import numpy as np

from navkit._shared.text import as_text
from navkit._shared.validation import positive_float
from navkit.errors import DataNotFoundError
from navkit.sim import Scenario, ScenarioResult, Scene, Table, Trial, TrialResult
from navkit.sim.scenarios._data import find_data
from navkit.sim.scenarios._demo_loop import (
    BODY_RADIUS,
    INFLATION_RADIUS,
    MAX_SPEED,
    PLAN_RADIUS,
    Setup,
    run_leg,
    setup,
)
from navkit.sim.scenarios._demo_maps import OFFICE_TOUR, WILLOW, WILLOW_TOUR

__all__ = ["Demo"]

MapChoice = Literal["auto", "willow", "office"]
_MAPS = ("auto", "willow", "office")
#: Shortest and longest simulated time per leg the option accepts, s.
_MIN_DURATION, _MAX_DURATION = 0.1, 3600.0
#: The values of a trial (what run_trial gives and summarize reads).
_KEYS = ("plan_length", "plan_wall_time", "travel_time", "final_error", "cross_track_mean",
         "cross_track_max", "estimate_error", "estimate_error_max", "min_clearance",
         "collisions", "reached", "distance", "willow")  # fmt: skip


class Demo(Scenario):
    """A robot plans, tracks and localises on a tour of a real office map.

    Each case is one leg of a three-leg tour. A trial plans the leg with A*
    (:class:`~navkit.planning.MapPlanner`, the robot's centre kept 0.3 m from
    walls and unknown space, costs decaying to 0.8 m so routes keep to the
    middle of corridors), then drives it in the simulator: a differential
    robot (0.3 m track, 0.2 m body, wheel slip and a 0.5 % wheel-radius error)
    with a 360-beam LiDAR, wheel encoders and an IMU;
    :class:`~navkit.estimation.PlanarFusion` fuses the encoders and the IMU,
    and :class:`~navkit.control.RegulatedPurePursuit` steers on that estimate
    (never on the true pose) at up to 0.5 m/s, slowed by the LiDAR when
    something is close ahead. Trials of a leg differ in their seed (sensor
    noise and slip).

    The map is the Willow Garage office (ROS map_server, 0.1 m cells) from the
    data folder (see :func:`~navkit.sim.scenarios.find_data`); without it, a
    synthetic 24 × 14 m office built in code. The table says which was used.
    The choice is made when the scenario is constructed, so a sweep's workers
    all use the same map (a worker without the data fails rather than
    switching maps).

    Trial values (SI units): ``plan_length``, ``plan_wall_time`` (wall clock,
    so not reproducible; every other value is), ``travel_time`` (until the
    tracker stopped, or the run ended), ``final_error`` (true distance to the
    goal at the end),
    ``cross_track_mean``, ``cross_track_max``, ``estimate_error`` (final),
    ``estimate_error_max``, ``min_clearance``, ``collisions``, ``reached``
    (0/1), ``distance`` and ``willow`` (1 on the Willow Garage map).

    Parameters
    ----------
    data_dir : str or path-like, optional
        The data folder (holding ``ros-map-server-maps``); default as
        :func:`~navkit.sim.scenarios.find_data`.
    map : {"auto", "willow", "office"}, default "auto"
        ``"auto"``: Willow Garage when its data is found, else the synthetic
        office; ``"willow"``: Willow Garage or :class:`DataNotFoundError`;
        ``"office"``: the synthetic office.
    duration : float, default 120.0
        Longest simulated time per leg, s, in [0.1, 3600] (the legs take 15 to
        55 s; a short one makes cheap trials for testing sweeps).

    Raises
    ------
    DataNotFoundError
        ``map="willow"`` and the map is not found.

    Examples
    --------
    >>> demo = Demo(map="office", duration=0.5)
    >>> result = demo.run(trials=1, seed=3)
    >>> [t.trial.case_index for t in result.trials]
    [0, 1, 2]
    >>> result.summary["collisions"], result.summary["willow"]
    (0.0, 0.0)
    """

    name = "demo"
    title = "plan (A*), track (regulated pure pursuit) and localise (fusion) on an office map"
    paper = "none: navkit's own end-to-end demonstration"
    default_trials = 1

    def __init__(
        self,
        *,
        data_dir: str | os.PathLike[str] | None = None,
        map: MapChoice = "auto",
        duration: float = 120.0,
    ) -> None:
        if data_dir is not None and not isinstance(data_dir, (str, os.PathLike)):
            raise TypeError(f"data_dir must be a path or None, got {type(data_dir).__name__}")
        if not isinstance(map, str):
            raise TypeError(f"map must be a str, got {type(map).__name__}")
        map = cast(MapChoice, as_text(map, "map"))  # checked and kept as the plain str
        if map not in _MAPS:
            raise ValueError(f"map must be one of {', '.join(_MAPS)}; got {map!r}")
        self.duration: float = positive_float(duration, "duration")
        if not _MIN_DURATION <= self.duration <= _MAX_DURATION:
            raise ValueError(
                f"duration must be in [{_MIN_DURATION:g}, {_MAX_DURATION:g}] s, got {self.duration}"
            )
        self.data_dir: str | None = None if data_dir is None else os.fspath(data_dir)
        self.map: MapChoice = map
        #: The map file used (None: the synthetic office), resolved now so that
        #: every worker of a sweep runs on the same map.
        self.map_path: str | None = None
        if map != "office":
            try:
                self.map_path = str(find_data(WILLOW, data_dir=self.data_dir).resolve())
            except DataNotFoundError:
                if map == "willow":
                    raise

    def __repr__(self) -> str:
        return f"Demo(data_dir={self.data_dir!r}, map={self.map!r}, duration={self.duration!r})"

    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        """The tour's legs, each run ``trials`` times.

        Parameters
        ----------
        trials : int
            Trials per leg.

        Returns
        -------
        tuple of (str, int)
            ``("leg 1: (x, y) -> (x, y) m", trials)`` for each leg.

        Examples
        --------
        >>> Demo(map="office").cases(2)[0]
        ('leg 1: (2.05, 3.05) -> (19.05, 11.55) m', 2)
        """
        trials = self._check_trials(trials)
        tour = OFFICE_TOUR if self.map_path is None else WILLOW_TOUR
        return tuple(
            (f"leg {i + 1}: ({a[0]:g}, {a[1]:g}) -> ({b[0]:g}, {b[1]:g}) m", trials)
            for i, (a, b) in enumerate(itertools.pairwise(tour))
        )

    def run_trial(self, trial: Trial) -> TrialResult:
        """Plan and drive one leg.

        Parameters
        ----------
        trial : Trial
            The leg (``case_index``) and the seed.

        Returns
        -------
        TrialResult
            The values listed in the class docstring and the trace.

        Examples
        --------
        >>> demo = Demo(map="office", duration=0.5)
        >>> r = demo.run_trial(demo.trials(1, seed=0)[0])
        >>> r.values["plan_length"] > 20.0, r.values["collisions"]
        (True, 0.0)
        """
        case = self._case_of(trial)
        leg = run_leg(setup(self.map_path), case, seed=trial.seed, duration=self.duration)
        m, trace = leg.trace.metrics, leg.trace
        error = np.hypot(*(trace.estimates[:, :2] - trace.poses[:, :2]).T)
        seen = error[np.isfinite(error)]
        values = {
            "plan_length": float(leg.route.length),
            "plan_wall_time": leg.plan_time,
            "travel_time": m.duration,
            "final_error": m.final_error,
            "cross_track_mean": m.cross_track_mean,
            "cross_track_max": m.cross_track_max,
            "estimate_error": m.estimate_error,
            "estimate_error_max": float(seen.max()) if seen.size else math.nan,
            "min_clearance": m.min_clearance,
            "collisions": float(m.collisions),
            "reached": float(m.reached),
            "distance": m.distance,
            "willow": float(self.map_path is not None),
        }
        return TrialResult(trial, values, trace)

    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
        """The tour's table: one row per leg (trials averaged) and the total.

        Parameters
        ----------
        results : sequence of TrialResult
            Every trial, in order.
        seed : int
            The base seed.

        Returns
        -------
        ScenarioResult
            One table; summary ``legs``, ``trials``, ``reached`` (share of
            trials), ``collisions`` (total), ``plan_length`` and
            ``travel_time`` (sums over the legs of the per-leg means),
            ``cross_track_max``, ``estimate_error_max`` (worst over all
            trials), ``estimate_error`` (mean final), ``plan_wall_time`` (sum
            of per-leg means, wall clock) and ``willow``.

        Examples
        --------
        >>> result = Demo(map="office", duration=0.2).run(trials=1)
        >>> print(result.table().splitlines()[0])
        navkit demo: plan, track and estimate on the synthetic office (24 x 14 m, built in code)
        """
        results, legs, seed = self._results_by_case(results, seed, keys=lambda _: _KEYS)
        if not results:
            raise ValueError("results: the demo needs at least one trial")
        scene = setup(self.map_path)

        def mean(rs: Sequence[TrialResult], key: str) -> float:
            return float(np.mean([r.values[key] for r in rs]))

        def worst(rs: Sequence[TrialResult], key: str) -> float:
            return float(np.max([r.values[key] for r in rs]))

        rows: list[tuple[str | float | None, ...]] = []
        for index, rs in sorted(legs.items()):
            rows.append((
                f"leg {index + 1}", mean(rs, "plan_length"), 1e3 * mean(rs, "plan_wall_time"),
                mean(rs, "travel_time"), 100.0 * mean(rs, "cross_track_mean"),
                100.0 * worst(rs, "cross_track_max"), 100.0 * mean(rs, "estimate_error"),
                100.0 * worst(rs, "estimate_error_max"),
                int(sum(r.values["collisions"] for r in rs)),
                f"{int(sum(r.values['reached'] for r in rs))}/{len(rs)}",
            ))  # fmt: skip
        everything = list(legs.values())
        summary = {
            "legs": float(len(legs)),
            "trials": float(len(results)),
            "reached": float(np.mean([r.values["reached"] for r in results])),
            "collisions": float(sum(r.values["collisions"] for r in results)),
            "plan_length": float(sum(mean(rs, "plan_length") for rs in everything)),
            "travel_time": float(sum(mean(rs, "travel_time") for rs in everything)),
            "cross_track_max": worst(results, "cross_track_max"),
            "estimate_error_max": worst(results, "estimate_error_max"),
            "estimate_error": mean(results, "estimate_error"),
            "plan_wall_time": float(sum(mean(rs, "plan_wall_time") for rs in everything)),
            "willow": float(self.map_path is not None),
        }
        rows.append((
            "tour", summary["plan_length"], 1e3 * summary["plan_wall_time"],
            summary["travel_time"], 100.0 * mean(results, "cross_track_mean"),
            100.0 * summary["cross_track_max"],
            100.0 * summary["estimate_error"], 100.0 * summary["estimate_error_max"],
            int(summary["collisions"]),
            f"{int(sum(r.values['reached'] for r in results))}/{len(results)}",
        ))  # fmt: skip
        n = len(results) // max(len(legs), 1)
        where = scene.label + ("" if self.map_path is None else f" ({self.map_path})")
        notes = (
            f"Map: {where}; {n} trial(s) per leg, base seed {seed}; at most {self.duration:g} s "
            "per leg.",
            f"Plan: A* (8-connected) keeping the centre {PLAN_RADIUS} m from walls and unknown "
            f"space, costs decaying to {INFLATION_RADIUS} m; plan time is wall clock on this "
            "machine.",
            f"Track: regulated pure pursuit at up to {MAX_SPEED} m/s on the fused estimate, "
            "slowed by the LiDAR near obstacles ahead; travel time until the tracker stops "
            "(estimate within 5 cm of the goal); reached = true position within 25 cm.",
            "Estimate: PlanarFusion of wheel encoders (4096 ticks/rev, 0.5 % radius error, "
            f"slip) and an IMU. Body radius {BODY_RADIUS} m.",
            "track = cross-track distance of the true path to the plan; est. error = final "
            "distance between estimated and true positions. Means over trials; the max columns "
            "are the worst trial. No paper to compare with: this is navkit's own demonstration.",
        )
        table = Table(
            f"navkit demo: plan, track and estimate on the {scene.label}",
            ("leg", "plan (m)", "plan (wall ms)", "travel (s)", "track mean (cm)",
             "track max (cm)", "est. error (cm)", "est. max (cm)", "collisions", "reached"),
            tuple(rows),
            notes,
        )  # fmt: skip
        return ScenarioResult(
            scenario=self.name,
            seed=seed,
            trials=tuple(results),
            tables=(table,),
            summary=summary,
            scene=_picture(scene, results),
        )


def _picture(scene: Setup, results: Sequence[TrialResult]) -> Scene:
    """The map, each leg's plan and its first trial's run (if kept), the waypoints."""
    paths, traces, seen = [], [], set()
    for r in results:
        index = r.trial.case_index
        if index in seen:
            continue
        seen.add(index)
        a, b = scene.tour[index], scene.tour[index + 1]
        paths.append((f"leg {index + 1} plan", scene.planner.plan(a, b).points))
        # A sweep with keep_traces=False: the plans are still worth drawing.
        if r.trace is not None:
            traces.append((f"leg {index + 1}", r.trace))
    return Scene(
        f"navkit demo on the {scene.label}",
        grid=scene.grid,
        paths=tuple(paths),
        traces=tuple(traces),
        points=(("waypoints", np.array(scene.tour, dtype=np.float64)),),
    )
