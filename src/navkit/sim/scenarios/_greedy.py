"""greedy: the TurtleBot3 Burger's greedy laser-grid planner on the TurtleBot3 world map."""

from __future__ import annotations

import math
import os
import time
from collections.abc import Sequence
from typing import Any

import numpy as np

from navkit._shared.validation import as_bool, as_float_array, positive_float
from navkit.errors import DataNotFoundError, NoPathError
from navkit.estimation import DiffOdometry
from navkit.geometry import Pose2D
from navkit.planning import Path2D
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
from navkit.sim.scenarios._data import find_data
from navkit.sim.scenarios._greedy_setup import (
    BODY_RADIUS,
    DRIVE,
    INFLATION,
    TICKS_PER_REV,
    GreedyController,
    astar_route,
    burger,
    tb3_map,
    tb3_world,
)

__all__ = ["MAP", "PAIRS", "Greedy"]

#: The TurtleBot3 world map inside the data folder.
MAP = "ros-map-server-maps/turtlebot3_world/map.yaml"
#: Start and goal (x, y) pairs in m: across the arena west to east and south to
#: north between the pillars, and along both diagonals, whose straight lines run
#: through three of the nine pillars.
PAIRS: tuple[tuple[tuple[float, float], tuple[float, float]], ...] = (
    ((-2.0, -0.5), (2.0, 0.5)),
    ((-0.5, -2.0), (0.5, 2.0)),
    ((-1.5, -1.5), (1.5, 1.5)),
    ((1.6, -1.6), (-1.6, 1.6)),
)
#: The goal counts as reached when the true position comes this close, m.
GOAL_RADIUS = 0.1
CONTROL_RATE = 10.0  # Hz
PHYSICS_RATE = 50.0  # Hz: at most 4.4 mm per step at 0.22 m/s
_MIN_DURATION = 0.1  # s
_MAX_DURATION = 3600.0  # s
_MAX_COORD = 1e4  # m
#: The values of a trial (what run_trial gives and summarize reads).
_KEYS = ("reached", "collisions", "time", "final_error", "path_length", "astar_length",
         "length_ratio", "min_clearance", "greedy_steps", "fallbacks")  # fmt: skip


def _pairs(value: Any) -> tuple[tuple[tuple[float, float], tuple[float, float]], ...]:
    if isinstance(value, (list, tuple)) and not value:
        # Read as shape (0,), which the shape check would report instead of the count.
        raise ValueError("pairs must hold 1 to 64 (start, goal) pairs, got 0")
    arr = as_float_array(value, "pairs", shape=(None, 2, 2))
    if not 1 <= arr.shape[0] <= 64:
        raise ValueError(f"pairs must hold 1 to 64 (start, goal) pairs, got {arr.shape[0]}")
    if float(np.max(np.abs(arr))) > _MAX_COORD:
        raise ValueError(f"pairs must lie within ±{_MAX_COORD:g} m")
    gap = np.hypot(arr[:, 1, 0] - arr[:, 0, 0], arr[:, 1, 1] - arr[:, 0, 1])
    close = np.flatnonzero(gap <= GOAL_RADIUS)
    if close.size:
        raise ValueError(
            f"pairs[{int(close[0])}]: the goal must lie more than {GOAL_RADIUS} m from the start"
        )
    return tuple(((float(sx), float(sy)), (float(gx), float(gy))) for (sx, sy), (gx, gy) in arr)


class Greedy(Scenario):
    """TurtleBot3 Burger: the greedy step on the 21 × 21 laser grid, on the TurtleBot3 world map.

    A TurtleBot3 Burger (differential drive: 0.16 m track, 33 mm wheels,
    0.22 m/s and 2.84 rad/s at most, a round body of 0.105 m radius) with a
    360-beam laser of 1 m range (the LDS-01 datasheet's accuracy as standard
    deviations: ±15 mm below 0.5 m, ±5 % beyond; 5 Hz; before review 49,
    without an absolute term, 3 % below 0.5 m)
    drives on its wheel odometry
    (:class:`~navkit.estimation.DiffOdometry`) across the map of the
    TurtleBot3 world (``ros-map-server-maps/turtlebot3_world``: a walled
    arena with nine pillars). At each scan the paper's 21 × 21 grid of 0.1 m
    cells (:meth:`~navkit.mapping.LaserScan.to_local_grid`) is built, its
    returns grown by ``inflation`` (0.25 m) so that a line of sight is a lane the body fits
    through, and :func:`~navkit.planning.greedy_step` picks the free, visible
    cell minimising robot→cell + cell→goal; the robot steers to it until the
    next scan. It stops when the odometry is within 5 cm of the goal. Each
    run is compared with A* on the full map (inflated by the body's radius).

    Start/goal pairs (m): (-2, -0.5) → (2, 0.5), (-0.5, -2) → (0.5, 2),
    (-1.5, -1.5) → (1.5, 1.5) and (1.6, -1.6) → (-1.6, 1.6); the robot starts
    facing its goal. Noisy trials (the default) add laser range noise drawn
    from each trial's seed (the wheels do not slip: the scenario measures the
    planner, not the odometry); with ``noise=False`` each pair runs once.

    Every option is keyword-only.

    Parameters
    ----------
    noise : bool, default True
        Laser range noise.
    pairs : sequence of ((x, y), (x, y)), default the four above
        Start and goal in m (at most 64 pairs, each goal more than 0.1 m from
        its start). When the map is found, each pair is checked as the
        scenario is built: the robot must fit at the start and A* must join
        it to the goal (a ``ValueError`` naming ``pairs[i]`` otherwise).
    duration : float, default 120.0
        Longest simulated time of a trial, s, in [0.1, 3600].
    inflation : float, default 0.25
        Growth of the local grid's returns, m, in [0, 1]; 0 is the paper's
        plain grid (on which every default pair ends in a collision: the
        greedy lines of sight graze the pillars).
    data_dir : str or path-like, optional
        The data folder holding ``ros-map-server-maps`` (see
        :func:`~navkit.sim.scenarios.find_data`). The map is looked up when
        the scenario is built, so that every worker of a sweep runs on that
        file; a trial raises :class:`~navkit.errors.DataNotFoundError` when it
        was not found.

    Raises
    ------
    TypeError
        ``noise`` not a bool, ``pairs``, ``duration`` or ``inflation`` not real
        numbers, ``data_dir`` not a path or None.
    ValueError
        ``inflation``, ``duration`` or the number of ``pairs`` outside its
        range, a goal within the goal radius of its start; with the map
        found, a start touching an obstacle or a goal A* cannot reach,
        naming the pair.

    Examples
    --------
    >>> scenario = Greedy(noise=False)
    >>> [case for case, _ in scenario.cases(10)][0]
    '(-2, -0.5) -> (2, 0.5) m'
    """

    name = "greedy"
    title = "TurtleBot3 Burger: greedy step on the 21 x 21 laser grid vs A*, TurtleBot3 world"
    paper = (
        "TurtleBot3 obstacle avoidance with a greedy planner on a 21 x 21 grid built from "
        "the laser scan (candidates in line of sight, minimum g + h)"
    )
    default_trials = 10

    def __init__(
        self,
        *,
        noise: bool = True,
        pairs: Sequence[Sequence[Sequence[float]]] = PAIRS,
        duration: float = 120.0,
        inflation: float = INFLATION,
        data_dir: str | os.PathLike[str] | None = None,
    ) -> None:
        self.noise: bool = as_bool(noise, "noise")
        self.inflation: float = positive_float(inflation, "inflation", allow_zero=True)
        if self.inflation > 1.0:
            raise ValueError(f"inflation must lie in [0, 1] m, got {self.inflation}")
        self.pairs: tuple[tuple[tuple[float, float], tuple[float, float]], ...] = _pairs(pairs)
        self.duration: float = positive_float(duration, "duration")
        if not _MIN_DURATION <= self.duration <= _MAX_DURATION:
            raise ValueError(
                f"duration must lie in [{_MIN_DURATION:g}, {_MAX_DURATION:g}] s, "
                f"got {self.duration}"
            )
        if data_dir is not None and not isinstance(data_dir, (str, os.PathLike)):
            raise TypeError(f"data_dir must be a path or None, got {type(data_dir).__name__}")
        self.data_dir: str | None = None if data_dir is None else os.fspath(data_dir)
        # The map is looked up once, here, as Demo and DiffAStar do theirs: a sweep's
        # workers (another working directory or $NAVKIT_DATA) then run on the same
        # map. Without it, each trial looks again and raises DataNotFoundError.
        try:
            self._map_file: str | None = str(find_data(MAP, data_dir=self.data_dir).resolve())
        except DataNotFoundError:
            self._map_file = None
        if self._map_file is not None:
            # Checked here, not at the end of a trial: a start in a pillar or a goal
            # A* cannot reach would otherwise fail only after the whole run.
            for index in range(len(self.pairs)):
                self._route(self._map_file, index)

    def __repr__(self) -> str:
        return (
            f"Greedy(noise={self.noise}, pairs={self.pairs}, duration={self.duration}, "
            f"inflation={self.inflation}, data_dir={self.data_dir!r})"
        )

    def _route(self, path: str, index: int) -> Path2D:
        """A*'s route for ``pairs[index]``; a ValueError naming the pair if it has none."""
        start, goal = self.pairs[index]
        heading = math.atan2(goal[1] - start[1], goal[0] - start[0])
        if tb3_world(path).collides(BODY_RADIUS, Pose2D(start[0], start[1], heading)):
            raise ValueError(
                f"pairs[{index}]: the robot at the start ({start[0]:g}, {start[1]:g}) "
                "touches or overlaps an obstacle of the map"
            )
        try:
            return astar_route(path, start, goal)
        except (ValueError, NoPathError) as exc:
            raise ValueError(f"pairs[{index}]: {exc}") from None

    def _map_path(self) -> str:
        if self._map_file is not None:
            return self._map_file
        return str(find_data(MAP, data_dir=self.data_dir))  # raises DataNotFoundError

    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        """One case per start/goal pair.

        Parameters
        ----------
        trials : int
            Trials per case (>= 1); a noise-free run has one per case.

        Returns
        -------
        tuple of (str, int)
            ``("(-2, -0.5) -> (2, 0.5) m", trials)`` and so on.

        Examples
        --------
        >>> Greedy(pairs=[((-2.0, -0.5), (-1.0, -0.5))]).cases(3)
        (('(-2, -0.5) -> (-1, -0.5) m', 3),)
        """
        trials = self._check_trials(trials)
        count = int(trials) if self.noise else 1
        return tuple(
            (f"({s[0]:g}, {s[1]:g}) -> ({g[0]:g}, {g[1]:g}) m", count) for s, g in self.pairs
        )

    def run_trial(self, trial: Trial) -> TrialResult:
        """Drive from the pair's start to its goal with the greedy step.

        Parameters
        ----------
        trial : Trial
            The pair and the seed of the noise.

        Returns
        -------
        TrialResult
            ``values``: ``reached`` (1 when the true position came within 0.1 m
            of the goal, the robot stopped there and touched nothing),
            ``collisions``, ``time`` (when the robot stopped, s; NaN if it did
            not), ``final_error`` (true final position to the goal, m),
            ``path_length`` (m driven), ``astar_length`` (A* on the full map,
            m), ``length_ratio`` (the two's ratio), ``min_clearance`` (m),
            ``greedy_steps`` and ``fallbacks`` (steps planned on the plain grid,
            the grown one leaving no line of sight); and the trace.

        Raises
        ------
        DataNotFoundError
            The TurtleBot3 world map is not in the data folder.
        ValueError
            The pair has no route (checked before the run, as in the
            constructor, when the map was found only now).

        Examples
        --------
        >>> import tempfile
        >>> from navkit.errors import DataNotFoundError
        >>> with tempfile.TemporaryDirectory() as empty:
        ...     scenario = Greedy(data_dir=empty)
        ...     try:
        ...         scenario.run_trial(scenario.trials(1)[0])
        ...     except DataNotFoundError:
        ...         print("no map")
        no map
        """
        index = self._case_of(trial)
        start, goal = self.pairs[index]
        path = self._map_path()
        began = time.perf_counter()
        # Before the run (the map may have been found only now): a pair A* cannot
        # join fails at once, not after the run.
        astar = float(self._route(path, index).length)
        heading = math.atan2(goal[1] - start[1], goal[0] - start[0])
        controller = GreedyController(goal, inflation=self.inflation)
        sim = Simulation(
            tb3_world(path),
            burger(self.noise),
            controller,
            start=(start[0], start[1], heading),
            goal=goal,
            goal_tolerance=GOAL_RADIUS,
            estimator=DiffOdometry(
                DRIVE, ticks_per_rev=TICKS_PER_REV, pose=(start[0], start[1], heading)
            ),
            rate=PHYSICS_RATE,
            control_rate=CONTROL_RATE,
            duration=self.duration,
            seed=trial.seed,
            stop_at_goal=False,
        )
        trace = sim.run()
        m = trace.metrics
        stopped = bool(controller.done)
        values = {
            "reached": 1.0 if stopped and m.collisions == 0 and m.final_error <= GOAL_RADIUS
            else 0.0,
            "collisions": float(m.collisions),
            "time": float(controller.arrived_at) if stopped else math.nan,
            "final_error": float(m.final_error),
            "path_length": float(m.distance),
            "astar_length": astar,
            "length_ratio": float(m.distance) / astar,
            "min_clearance": float(m.min_clearance),
            "greedy_steps": float(controller.steps),
            "fallbacks": float(controller.fallbacks),
        }  # fmt: skip
        return TrialResult(trial, values, trace, time.perf_counter() - began)

    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
        """Success, collisions and path length against A*, pair by pair.

        Parameters
        ----------
        results : sequence of TrialResult
            Every trial of :meth:`trials`, in order.
        seed : int
            The run's base seed.

        Returns
        -------
        ScenarioResult
            One table; the summary (``success_rate``, ``collisions``,
            ``length_ratio_mean``, ``length_ratio_max``, ``time_mean``,
            ``final_error_max``, ``min_clearance``, ``trials``); a scene with
            the map, A*'s paths, one trace per pair and the starts and goals.

        Examples
        --------
        >>> Greedy().summarize([], seed=0).summary["trials"]
        0.0
        """
        results, by_case, seed = self._results_by_case(results, seed, keys=lambda _: _KEYS)
        return ScenarioResult(
            scenario=self.name,
            seed=seed,
            trials=results,
            tables=(self._table(by_case),),
            summary=_summary(results),
            scene=self._scene(by_case) if results else None,
        )

    def _table(self, by_case: dict[int, list[TrialResult]]) -> Table:
        rows = []
        for index in sorted(by_case):
            group = by_case[index]
            col = {k: np.array([r.values[k] for r in group], dtype=np.float64)
                   for k in ("reached", "collisions", "time", "path_length", "astar_length",
                             "length_ratio", "min_clearance")}  # fmt: skip
            rows.append(
                (
                    group[0].trial.case,
                    len(group),
                    100.0 * float(col["reached"].mean()),
                    int(col["collisions"].sum()),
                    _nanmean(col["time"]),
                    float(col["path_length"].mean()),
                    float(col["astar_length"][0]),
                    float(col["length_ratio"].mean()),
                    float(col["min_clearance"].min()),
                )
            )
        noise = "laser noise" if self.noise else "noise-free"
        grown = f"returns grown by {self.inflation:g} m" if self.inflation else "plain grid"
        return Table(
            f"Greedy step on the 21 x 21 laser grid against A* on the full map ({noise}, {grown})",
            ("start -> goal", "trials", "success (%)", "collisions", "mean time (s)",
             "mean path (m)", "A* path (m)", "path / A*", "min clearance (m)"),
            tuple(rows),
            (
                "success: the robot stopped on its odometry within 0.05 m of the goal, its true "
                "position within 0.1 m, without touching anything. A*: 8-connected on the full "
                "map, inflated by the body's 0.105 m radius.",
                "The paper (TurtleBot3 in the TurtleBot3 world) shows the robot reaching its "
                "goals around obstacles; it publishes no success rates or lengths to put beside "
                "these. navkit grows the local grid's returns (0.25 m by default; the paper does "
                "not): on the plain grid (inflation=0) every default pair ends in a collision, "
                "the greedy lines of sight grazing the pillars.",
            ),
        )  # fmt: skip

    def _scene(self, by_case: dict[int, list[TrialResult]]) -> Scene:
        path = self._map_path()
        traces: list[tuple[str, Trace]] = []
        routes = []
        for index in sorted(by_case):
            first = by_case[index][0]
            if first.trace is not None:
                traces.append((f"greedy {first.trial.case}", first.trace))
            start, goal = self.pairs[index]
            routes.append((f"A* {first.trial.case}", astar_route(path, start, goal).points))
        pairs = [self.pairs[i] for i in sorted(by_case)]
        return Scene(
            "greedy: TurtleBot3 Burger on the TurtleBot3 world map",
            grid=tb3_map(path),
            paths=tuple(routes),
            traces=tuple(traces),
            points=(
                ("starts", np.array([s for s, _ in pairs], dtype=np.float64)),
                ("goals", np.array([g for _, g in pairs], dtype=np.float64)),
            ),
        )


def _nanmean(values: np.ndarray) -> float:
    finite = values[np.isfinite(values)]
    return float(finite.mean()) if finite.size else math.nan


def _summary(results: Sequence[TrialResult]) -> dict[str, float]:
    if not results:
        return {"trials": 0.0}
    col = {k: np.array([r.values[k] for r in results], dtype=np.float64)
           for k in ("reached", "collisions", "length_ratio", "time", "final_error",
                     "min_clearance")}  # fmt: skip
    return {
        "success_rate": float(col["reached"].mean()),
        "collisions": float(col["collisions"].sum()),
        "length_ratio_mean": float(col["length_ratio"].mean()),
        "length_ratio_max": float(col["length_ratio"].max()),
        "time_mean": _nanmean(col["time"]),
        "final_error_max": float(col["final_error"].max()),
        "min_clearance": float(col["min_clearance"].min()),
        "trials": float(len(results)),
    }
