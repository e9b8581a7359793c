"""``soccer``: the wheeled soccer robot's potential-field play and the paper's Table 6.

The paper's robot (ROS Noetic) drives on a blended-sigmoid attraction with
Khatib repulsion through an acceleration-limited motion algorithm with a
heading PID, and plays single attack, support and defence against opponents.
Here it plays those roles in :mod:`navkit.sim` on a RoboCup Middle Size League
field against static and moving opponents (the paper's obstacle variations,
as chosen and listed in :data:`LAYOUTS`), and the potentials of its Table 6
are recomputed on the 1200 × 1200 map.
"""

from __future__ import annotations

import functools
import math
import time
from collections.abc import Sequence
from typing import Any

import numpy as np

from navkit._shared.validation import bounded_int, finite_float
from navkit.kinematics import OmniDrive
from navkit.sim import Robot, Scenario, ScenarioResult, Scene, Simulation, Table, Trial, TrialResult
from navkit.sim.scenarios._soccer_play import (
    FIELD_LENGTH,
    FIELD_WIDTH,
    GOAL_WIDTH,
    INFLUENCE_RADIUS,
    K_REP,
    LAYOUTS,
    MAX_ACCEL,
    MAX_DECEL,
    OPPONENT_GOAL,
    OWN_GOAL,
    PLAYER_RADIUS,
    POSSESSION_RADIUS,
    Player,
    make_game,
    player_attraction,
)
from navkit.sim.scenarios._soccer_table6 import (
    FULL_TABLE_CELLS,
    RESOLUTION,
    THRESHOLD_RADIUS,
    WIDTHS_PX,
    radial_minima,
    table6_values,
)

__all__ = ["Soccer"]

#: Physics and control rates, Hz.
PHYSICS_RATE = 100.0
CONTROL_RATE = 30.0
#: The paper's ranges of times, s.
PAPER_ATTACK = (5.07, 13.47)
PAPER_DEFEND = (5.17, 7.36)
_SUCCESS = ("scored", "ball taken", "in position")
_GAME_KEYS = ("reached", "collisions", "stalled", "time", "time_to_ball", "distance",
              "min_clearance", "opponents")  # fmt: skip
_TABLE6_KEYS = (
    "linear_min",
    "paraboloid_min",
    *(
        f"w{px}_{what}"
        for px in WIDTHS_PX
        for what in ("blended_min", "min_radius", "false_minima", "ring_radius", "trap_depth")
    ),
)
_GAME_COLUMNS = (
    "case", "trials", "reached", "collisions", "stalled", "time mean (s)", "time min (s)",
    "time max (s)", "path (m)", "min clearance (m)", "paper time (s)",
)  # fmt: skip
_TABLE6_COLUMNS = (
    "width (cells)", "width (m)", "linear min", "paraboloid min", "blended min",
    "blended min at (m)", "false minima", "ring radius (m)", "trap depth",
)  # fmt: skip
_TABLE6_CASE = "Table 6: potential minima, blending widths 1, 10, 50, 100 cells"


@functools.lru_cache(maxsize=8)
def _robot(wheel_slip: float) -> Robot:
    """A 3-wheel omni soccer robot (wheels at 30°, 150°, 270°), 0.25 m round body."""
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    return Robot(drive=drive, footprint=PLAYER_RADIUS, max_wheel_speed=100.0,
                 max_wheel_acceleration=80.0, wheel_slip=wheel_slip)  # fmt: skip


def _option(value: Any, name: str, low: float, high: float, unit: str) -> float:
    out = finite_float(value, name)
    if not low <= out <= high:
        # repr, not :g: 0.5000001 printed as "0.5" would look inside [0, 0.5].
        units = f" {unit}" if unit else ""
        raise ValueError(f"{name} must lie in [{low:g}, {high:g}]{units}, got {out!r}")
    return out


class Soccer(Scenario):
    """The wheeled soccer robot: attack, support and defence against opponents; Table 6.

    Nine game cases (see :data:`~navkit.sim.scenarios._soccer_play.LAYOUTS`):
    attack with 0, 1, 2 or 3 static opponents on the way and with 1 static + 2
    moving ones; defence against an opponent dribbling at the own goal, alone,
    with 1 static or with 2 moving opponents; support with a teammate on the
    ball and 1 static + 1 moving opponent. Each trial places the players at
    random (seeded) around the case's layout and runs the closed loop; it
    reports whether the robot reached (scored, took the ball, got into
    position), collisions, stalls and times. One deterministic case
    recomputes the paper's Table 6 (run once whatever ``trials`` is).

    Every option is keyword-only.

    Parameters
    ----------
    max_speed : float, default 1.5
        The robot's top speed (m/s), in [0.2, 5]; also the cone's gradient ``m``,
        with ``K_att = max_speed / 0.75`` (2 at the default), so that the blended
        attraction has no false minimum at any top speed. Faster is not
        safer: braking at 3 m/s², the robot needs ``max_speed² / 6`` m to stop,
        1 m at 2.45 m/s, all there is between the repulsion's reach (1.5 m
        between centres) and contact (0.5 m), so it hits opponents on its way
        (3 trials a case, seed 0: 100 % of the games reached at 1.5 m/s, 89 %
        at 2, 37 % at 2.5, 30 % at 3).
    perception_noise : float, default 0.02
        Standard deviation (m) of the seen positions of the ball and the other
        robots, in [0, 0.5].
    wheel_slip : float, default 0.02
        The simulated wheels' slip scale, in [0, 0.5].
    duration : float, default 40.0
        Longest simulated time of a trial (s), in [0.1, 600].
    table_cells : int, default 1200
        Side of the Table 6 map in 1 cm cells, in [50, 1200] (the paper's
        1200); its features lie within 0.6 m of the goal, so 120 cells or more
        give the same figures. A smaller map cuts the ring of false minima
        (out to 0.55 m from the goal) off the grid: its 'false minima' counts
        fall short (the table says so).

    Raises
    ------
    TypeError
        A number not a real number (``table_cells`` not an integer).
    ValueError
        A value NaN, infinite or outside its documented range, naming it.

    Examples
    --------
    >>> scenario = Soccer(duration=20.0)
    >>> [case for case, _ in scenario.cases(2)][:2]
    ['attack, no opponent', 'attack, 1 static opponent on the way']
    >>> trial = scenario.trials(1, seed=0)[0]
    >>> scenario.run_trial(trial).values["reached"]
    1.0
    """

    name = "soccer"
    title = "wheeled soccer robot: blended attraction, Khatib repulsion, attack/support/defence"
    paper = (
        "A wheeled soccer robot (ROS Noetic): blended-sigmoid attractive potential, Khatib "
        "repulsion, acceleration-limited motion with heading PID, attack/support/defence"
    )
    default_trials = 10

    def __init__(
        self,
        *,
        max_speed: float = 1.5,
        perception_noise: float = 0.02,
        wheel_slip: float = 0.02,
        duration: float = 40.0,
        table_cells: int = 1200,
    ) -> None:
        self.max_speed: float = _option(max_speed, "max_speed", 0.2, 5.0, "m/s")
        self.perception_noise: float = _option(perception_noise, "perception_noise", 0.0, 0.5, "m")
        self.wheel_slip: float = _option(wheel_slip, "wheel_slip", 0.0, 0.5, "")
        self.duration: float = _option(duration, "duration", 0.1, 600.0, "s")
        self.table_cells: int = bounded_int(table_cells, "table_cells", 50, 1200)

    def __repr__(self) -> str:
        return (
            f"Soccer(max_speed={self.max_speed}, perception_noise={self.perception_noise}, "
            f"wheel_slip={self.wheel_slip}, duration={self.duration}, "
            f"table_cells={self.table_cells})"
        )

    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        """The nine game cases with ``trials`` each, then Table 6 once.

        Parameters
        ----------
        trials : int
            Trials per game case, in [1, 100000].

        Returns
        -------
        tuple of (str, int)
            ``(case, trials)`` in order.

        Examples
        --------
        >>> Soccer().cases(3)[-1]
        ('Table 6: potential minima, blending widths 1, 10, 50, 100 cells', 1)
        """
        trials = self._check_trials(trials)
        return (*((layout.label, trials) for layout in LAYOUTS), (_TABLE6_CASE, 1))

    def run_trial(self, trial: Trial) -> TrialResult:
        """Play one game (or recompute Table 6 for its case).

        Parameters
        ----------
        trial : Trial
            Its ``case_index`` picks the case, its ``seed`` the placement,
            perception noise and wheel slip.

        Returns
        -------
        TrialResult
            A game's ``reached``, ``collisions``, ``stalled``, ``time`` (s, to
            score / take the ball / get into position; NaN if not reached),
            ``time_to_ball`` (s), ``distance`` (m), ``min_clearance`` (m) and
            ``opponents``, with the trace; Table 6's figures without one.

        Examples
        --------
        >>> scenario = Soccer(table_cells=200)
        >>> trial = scenario.trials(1)[-1]
        >>> scenario.run_trial(trial).values["linear_min"]
        -0.5
        """
        case = self._case_of(trial)
        start = time.perf_counter()
        if case == len(LAYOUTS):
            values = dict(table6_values(self.table_cells))
            return TrialResult(trial, values, None, time.perf_counter() - start)
        layout = LAYOUTS[case]
        game = make_game(layout, trial.seed)
        # Perception noise and the simulation (wheel slip) get streams of their own,
        # independent of the placement's: seeded alike, all three drew the same numbers.
        noise_seed, sim_seed = np.random.SeedSequence(trial.seed).spawn(2)
        player = Player(game, max_speed=self.max_speed, control_rate=CONTROL_RATE,
                        noise=self.perception_noise, seed=noise_seed)  # fmt: skip
        trace = Simulation(
            game.world, _robot(self.wheel_slip), player, start=game.start, rate=PHYSICS_RATE,
            control_rate=CONTROL_RATE, duration=self.duration, seed=np.random.default_rng(sim_seed),
        ).run()  # fmt: skip
        m = trace.metrics
        reached = player.outcome in _SUCCESS and m.collisions == 0
        values = {  # the keys are _GAME_KEYS
            "reached": float(reached),
            "collisions": float(m.collisions),
            "stalled": float(player.outcome == "stalled"),
            "time": player.t_done if reached else math.nan,
            "time_to_ball": player.t_ball,
            "distance": m.distance,
            "min_clearance": m.min_clearance,
            "opponents": float(len(game.opponents) + game.static_xy.shape[0]),
        }
        return TrialResult(trial, values, trace, time.perf_counter() - start)

    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
        """The games' table beside the paper's times, and Table 6 recomputed.

        Parameters
        ----------
        results : sequence of TrialResult
            The trials of :meth:`trials`, in order.
        seed : int
            The base seed.

        Returns
        -------
        ScenarioResult
            Two tables, the headline figures in ``summary`` and a scene of one
            attack with 3 opponents (and one defence).

        Examples
        --------
        >>> scenario = Soccer(table_cells=200, duration=20.0)
        >>> trials = [t for t in scenario.trials(1) if t.case_index in (0, 9)]
        >>> result = scenario.summarize([scenario.run_trial(t) for t in trials], seed=0)
        >>> result.summary["reach_rate"], result.summary["collisions"]
        (1.0, 0.0)
        """
        results, by_case, seed = self._results_by_case(
            results, seed, keys=lambda case: _TABLE6_KEYS if case == len(LAYOUTS) else _GAME_KEYS
        )
        games = {case: runs for case, runs in by_case.items() if case < len(LAYOUTS)}
        table6 = dict(by_case[len(LAYOUTS)][-1].values) if len(LAYOUTS) in by_case else None
        tables = [self._games_table(games)]
        summary = _game_summary(games)
        if table6 is not None:
            tables.append(self._table6(table6))
            summary.update({f"table6_{k}": float(v) for k, v in table6.items()})
        return ScenarioResult(
            self.name, int(seed), results, tuple(tables), summary, self._scene(games)
        )

    # ------------------------------------------------------------------ tables
    def _games_table(self, games: dict[int, list[TrialResult]]) -> Table:
        rows: list[tuple[Any, ...]] = []
        for role, paper in (("attack", PAPER_ATTACK), ("defend", PAPER_DEFEND),
                            ("support", None)):  # fmt: skip
            chosen = [i for i, layout in enumerate(LAYOUTS) if layout.role == role]
            paper_text = "-" if paper is None else f"{paper[0]:.2f}-{paper[1]:.2f}"
            for i in chosen:
                if i in games:
                    rows.append(_row(LAYOUTS[i].label, games[i], paper_text))
            everything = [r for i in chosen for r in games.get(i, [])]
            if everything and len(chosen) > 1:
                rows.append(_row(f"{role}, all variations", everything, paper_text))
        hx, hy = 0.5 * FIELD_LENGTH, 0.5 * FIELD_WIDTH
        notes = (
            f"Field: RoboCup Middle Size League, {FIELD_LENGTH:g} x {FIELD_WIDTH:g} m inside the "
            f"lines (x in ±{hx:g}, y in ±{hy:g} m), goals {GOAL_WIDTH:g} m wide at x = ±{hx:g} m, "
            "a wall 1 m outside the lines. Robots are 0.25 m discs; the ball (0.11 m) is taken "
            f"within {POSSESSION_RADIUS:g} m of its centre and then held in front of the robot.",
            f"Robot: 3-wheel omni, top speed {self.max_speed:g} m/s, accel {MAX_ACCEL:g} / decel "
            f"{MAX_DECEL:g} m/s², heading PID (kp 4, kd 0.1); BlendedAttraction K_att "
            f"{player_attraction(self.max_speed).k_att:.3g}, "
            f"rad_thr 0.5 m, width 0.15 m, m = top speed; Khatib k_rep {K_REP:g}, "
            f"d0 {INFLUENCE_RADIUS:g} m on the other robots' centres; control "
            f"{CONTROL_RATE:g} Hz, physics {PHYSICS_RATE:g} Hz, wheel slip {self.wheel_slip:g}, "
            f"seen positions with {self.perception_noise * 1000:g} mm noise, true pose.",
            "Attack: from x ≈ -5 m to the ball at x ≈ -1 m, then carried into the opponents' goal "
            "(time = ball over the goal line). Defence: an opponent dribbles from x ≈ 2 m towards "
            "the own goal at 0.5-0.8 m/s; time = ball taken. Support: to the midpoint of the "
            "ball and the own goal (within 0.15 m).",
            "Obstacle variations (the paper's numbers of opponents, placed by navkit): static "
            "opponents stand on the robot's way with their centres 0.1-0.35 m off its line (a "
            "centre exactly on it would balance attraction and repulsion); moving ones cross "
            "the way back and forth over ±2 m at 0.4-0.8 m/s.",
            "'reached' counts runs that scored / took the ball / got into position without a "
            "collision; the paper reports times only (attack 5.07-13.47 s, defence 5.17-7.36 s) "
            "on its own, shorter field; compare time per metre with the path column.",
        )
        return Table(
            "Soccer games: reach, collisions and times, navkit beside the paper",
            _GAME_COLUMNS,
            tuple(rows),
            notes,
        )

    def _table6(self, values: dict[str, float]) -> Table:
        rows = []
        for px in WIDTHS_PX:
            rows.append((
                px, px * RESOLUTION, values["linear_min"], values["paraboloid_min"],
                values[f"w{px}_blended_min"], values[f"w{px}_min_radius"],
                values[f"w{px}_false_minima"], values[f"w{px}_ring_radius"],
                values[f"w{px}_trap_depth"],
            ))  # fmt: skip
        player = player_attraction(self.max_speed)
        lows, _ = radial_minima(player)
        side = self.table_cells
        notes = (
            f"Recomputed on a {side} x {side} map of 1 cm cells (the paper's 1200 x 1200 map, "
            f"one map unit = 1 cm), goal at a cell centre; K_att = c = a = b = m = U_trans = 1, "
            f"rad_thr = {THRESHOLD_RADIUS:g} m (navkit's defaults: the paper's own parameters and "
            "printed values are not in navkit's sources, so no paper column).",
            "What it shows: the linear (cone) minimum is -m·U_trans·rad_thr at the goal and the "
            "paraboloid's 0 at the goal, whatever the width. The blend as the paper writes it "
            "keeps the paraboloid's minimum for narrow widths (1 and 10 cells) but adds a ring of "
            "false minima just outside rad_thr, where the σ'(U_cone - U_par) term pulls outward "
            "(a robot stalls there: tests/control/test_blending_widths.py); wide widths (50, 100 "
            "cells) have no ring but mix the cone's negative offset in (σ(0) > 0): the minimum "
            "drops below 0, and at 50 cells it is a circle around the goal, not the goal."
            + (
                ""
                if side >= FULL_TABLE_CELLS
                else f" (On this {side}-cell map the ring, out to 0.55 m from the goal, lies "
                "partly or wholly off the grid: the 'false minima' column counts only its cells "
                f"on the map; {FULL_TABLE_CELLS} cells or more give the full counts.)"
            ),
            "'min at (m)': radius of the blended potential's lowest point from the goal (radial "
            "profile, 0.1 mm steps); 'false minima': grid cells below their 8 neighbours farther "
            "than rad_thr/2 from the goal; 'trap depth': potential climb from the ring over the "
            "crest inside it.",
            "navkit's answer: the formula is implemented as stated and its defaults avoid both "
            f"failures; the robot above uses K_att {player.k_att:.3g}, rad_thr 0.5 m, "
            "width 0.15 m, m = "
            f"{self.max_speed:g}: its radial profile has one minimum, "
            f"{1000 * float(lows[0]):.1f} mm from the goal, and no false minimum"
            if lows.size == 1
            else "navkit's answer: the formula is implemented as stated; the robot above uses "
            f"K_att {player.k_att:.3g}, rad_thr 0.5 m, width 0.15 m, m = {self.max_speed:g}, "
            "whose radial profile "
            f"has minima at {', '.join(f'{v:.3f}' for v in lows)} m",
        )
        return Table(
            "Table 6 recomputed: minima of the linear, paraboloid and blended potentials",
            _TABLE6_COLUMNS,
            tuple(rows),
            notes,
        )

    def _scene(self, games: dict[int, list[TrialResult]]) -> Scene:
        picks = [i for i in (3, 5) if games.get(i)]
        if not picks:
            picks = sorted(games)[:1]
        if not picks:
            return Scene("soccer: no game was run")
        first = games[picks[0]][0]
        game = make_game(LAYOUTS[first.trial.case_index], first.trial.seed)
        traces = tuple(
            (LAYOUTS[i].label, trace) for i in picks if (trace := games[i][0].trace) is not None
        )
        paths = tuple(
            (f"opponent {k + 1} path", np.asarray(ob.path_xy))
            for k, ob in enumerate(game.opponents)
        )
        points = (
            ("goals", np.stack((OWN_GOAL, OPPONENT_GOAL))),
            ("ball", game.ball_xy[None, :]),
            ("start", np.array([game.start[:2]])),
        )
        return Scene(f"soccer: {game.layout.label}", world=game.world, paths=paths,
                     traces=traces, points=points)  # fmt: skip


def _row(label: str, results: list[TrialResult], paper: str) -> tuple[Any, ...]:
    values = {k: np.array([r.values[k] for r in results]) for k in results[0].values}
    times = values["time"][np.isfinite(values["time"])]
    return (
        label,
        len(results),
        f"{int(values['reached'].sum())}/{len(results)}",
        int(values["collisions"].sum()),
        int(values["stalled"].sum()),
        float(times.mean()) if times.size else math.nan,
        float(times.min()) if times.size else math.nan,
        float(times.max()) if times.size else math.nan,
        float(values["distance"].mean()),
        float(values["min_clearance"].min()),
        paper,
    )


def _game_summary(games: dict[int, list[TrialResult]]) -> dict[str, float]:
    every = [r for rs in games.values() for r in rs]
    out: dict[str, float] = {
        "games": float(len(every)),
        "reach_rate": (float(np.mean([r.values["reached"] for r in every])) if every else math.nan),
        "collisions": float(sum(r.values["collisions"] for r in every)),
        "stalls": float(sum(r.values["stalled"] for r in every)),
        "min_clearance": (
            float(min(r.values["min_clearance"] for r in every)) if every else math.nan
        ),
    }
    for role in ("attack", "defend", "support"):
        times = np.array([
            r.values["time"] for i, rs in games.items() if LAYOUTS[i].role == role for r in rs
        ])  # fmt: skip
        times = times[np.isfinite(times)]
        for stat in ("min", "mean", "max"):
            out[f"{role}_time_{stat}"] = float(getattr(times, stat)()) if times.size else math.nan
    return out
