"""The soccer scenario's games: the field, the obstacle variations and the player.

A RoboCup Middle Size League field (18 × 12 m inside the lines, goals 2 m wide
on the short sides, a wall 1 m outside the lines) holds one navkit robot, the
ball, opponents (static discs or :class:`~navkit.sim.MovingObstacle` s) and,
for support, a teammate. :class:`Player` is the closed-loop controller: every
control step it builds a :class:`~navkit.behaviours.GameState` from what the
robot sees (true positions plus Gaussian perception noise), asks the role
(:func:`~navkit.behaviours.attack`, :func:`~navkit.behaviours.support` or
:func:`~navkit.behaviours.defend`) for the goal and the repelling points, and
steps a :class:`~navkit.control.PotentialFieldController` (blended-sigmoid
attraction, Khatib repulsion, acceleration limits, heading PID) on them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from shapely.geometry import LineString, box
from shapely.geometry.base import BaseGeometry

from navkit._shared.frozen import frozen_setattr
from navkit._shared.types import FloatArray
from navkit.behaviours import GameState, attack, defend, support
from navkit.control import PotentialFieldController
from navkit.geometry import Twist2D
from navkit.planning import BlendedAttraction
from navkit.sim import Circle, MovingObstacle, Observation, World

__all__ = [
    "BALL_RADIUS",
    "FIELD_LENGTH",
    "FIELD_WIDTH",
    "GOAL_WIDTH",
    "LAYOUTS",
    "PLAYER_RADIUS",
    "Game",
    "Layout",
    "Player",
    "field_world",
    "make_game",
    "player_attraction",
]

Role = Literal["attack", "defend", "support"]

#: RoboCup MSL field inside the lines (m): x in ±9, y in ±6.
FIELD_LENGTH = 18.0
FIELD_WIDTH = 12.0
#: Goal mouth (m), centred on the short sides.
GOAL_WIDTH = 2.0
#: Run-off between the lines and the surrounding wall (m).
RUN_OFF = 1.0
#: Radius of every robot's round footprint (m): MSL robots fit in 0.52 × 0.52 m.
PLAYER_RADIUS = 0.25
#: FIFA size-5 ball (m).
BALL_RADIUS = 0.11
#: Centre distance of a ball held in front of a robot (touching it).
HOLD_DISTANCE = PLAYER_RADIUS + BALL_RADIUS
#: A robot within this distance of the ball's centre holds it (or takes it).
POSSESSION_RADIUS = 0.45
#: Support has arrived within this distance of its point (m).
SUPPORT_TOLERANCE = 0.15
#: Goal post radius (m).
POST_RADIUS = 0.06
#: Centres of the goal the robot defends and of the one it attacks (read-only).
OWN_GOAL: FloatArray = np.array([-0.5 * FIELD_LENGTH, 0.0])
OPPONENT_GOAL: FloatArray = np.array([0.5 * FIELD_LENGTH, 0.0])
OWN_GOAL.setflags(write=False)
OPPONENT_GOAL.setflags(write=False)
#: Khatib gain and d0 (m) on the other robots' centres, and the acceleration limits (m/s²).
K_REP = 1.0
INFLUENCE_RADIUS = 1.5
MAX_ACCEL = 1.5
MAX_DECEL = 3.0


def field_world(static_xy: FloatArray, moving: tuple[MovingObstacle, ...]) -> World:
    """The field's wall and goal frames, static robots (discs) and moving ones."""
    hx = 0.5 * FIELD_LENGTH
    hy = 0.5 * FIELD_WIDTH
    half_goal = 0.5 * GOAL_WIDTH
    items: list[BaseGeometry | Circle] = [
        box(-hx - RUN_OFF, -hy - RUN_OFF, hx + RUN_OFF, hy + RUN_OFF).exterior
    ]
    for side in (-1.0, 1.0):
        x = side * hx
        back = side * (hx + 0.5)
        items.append(LineString([(x, half_goal), (back, half_goal), (back, -half_goal),
                                 (x, -half_goal)]))  # fmt: skip
        items.extend(Circle(np.array([x, s * half_goal]), POST_RADIUS) for s in (-1.0, 1.0))
    items.extend(Circle(p, PLAYER_RADIUS) for p in static_xy)
    return World(items, moving=moving)


@frozen_setattr
@dataclass(frozen=True, slots=True)
class Layout:
    """One obstacle variation of the paper's experiments.

    Attributes
    ----------
    label : str
        What the case is, for people.
    role : {"attack", "defend", "support"}
    static : int
        Opponents standing still on the way.
    moving : int
        Opponents crossing the way back and forth.
    """

    label: str
    role: Role
    static: int
    moving: int


#: The obstacle variations, in the scenario's order.
LAYOUTS: tuple[Layout, ...] = (
    Layout("attack, no opponent", "attack", 0, 0),
    Layout("attack, 1 static opponent on the way", "attack", 1, 0),
    Layout("attack, 2 static opponents on the way", "attack", 2, 0),
    Layout("attack, 3 static opponents on the way", "attack", 3, 0),
    Layout("attack, 1 static + 2 moving opponents", "attack", 1, 2),
    Layout("defend, opponent dribbling at the own goal", "defend", 0, 0),
    Layout("defend, + 1 static opponent on the way", "defend", 1, 0),
    Layout("defend, + 2 moving opponents", "defend", 0, 2),
    Layout("support, teammate on the ball, 1 static + 1 moving opponent", "support", 1, 1),
)


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class Game:
    """Everything one trial needs: start, world, ball and the other players.

    ``holder`` is the opponent dribbling the ball (defence), ``mate_xy`` the
    teammate holding it (support); opponents are ``opponents`` (moving, holder
    first) and ``static_xy``.
    """

    layout: Layout
    start: tuple[float, float, float]
    ball_xy: FloatArray
    static_xy: FloatArray
    opponents: tuple[MovingObstacle, ...]
    holder: MovingObstacle | None
    mate_xy: FloatArray | None
    world: World


def _unit(v: FloatArray) -> FloatArray:
    n = float(np.hypot(v[0], v[1]))
    out: FloatArray = v / n
    return out


def _on_the_way(rng: np.random.Generator, a: FloatArray, b: FloatArray, frac: float) -> FloatArray:
    """A point near ``a + frac·(b - a)``, its centre 0.1–0.35 m off the line (it blocks it).

    A centre exactly on the robot's line would balance attraction and the radial
    repulsion (a saddle of the field); the paper placed its obstacles by hand.
    """
    d = _unit(b - a)
    n = np.array([-d[1], d[0]])
    along = rng.uniform(-0.3, 0.3)
    side = 1.0 if rng.random() < 0.5 else -1.0
    out: FloatArray = a + frac * (b - a) + along * d + side * rng.uniform(0.1, 0.35) * n
    return out


def _crossing(
    rng: np.random.Generator, a: FloatArray, b: FloatArray, frac: float
) -> MovingObstacle:
    """An opponent going back and forth across the line ``a → b`` (±2 m) at 0.4–0.8 m/s."""
    d = _unit(b - a)
    n = np.array([-d[1], d[0]])
    centre = a + frac * (b - a) + rng.uniform(-0.3, 0.3) * d
    span = 2.0
    speed = rng.uniform(0.4, 0.8)
    period = 4.0 * span / speed
    path = np.stack((centre - span * n, centre + span * n, centre - span * n))
    phase = rng.uniform(0.0, period)
    times = np.array([0.0, 0.5 * period, period]) - phase
    return MovingObstacle(PLAYER_RADIUS, path, times, after="loop")


def make_game(layout: Layout, seed: int) -> Game:
    """Place the robot, the ball and the other players of one trial (seeded)."""
    rng = np.random.default_rng(seed)
    goal = OPPONENT_GOAL
    own = OWN_GOAL
    holder: MovingObstacle | None = None
    mate: FloatArray | None = None
    static: list[FloatArray] = []
    moving: list[MovingObstacle] = []
    if layout.role == "attack":
        robot = np.array([rng.uniform(-5.5, -4.5), rng.uniform(-1.5, 1.5)])
        ball = np.array([rng.uniform(-1.5, -0.5), rng.uniform(-1.0, 1.0)])
        spots = [(robot, ball, 0.5), (ball, goal, 0.35), (ball, goal, 0.7)]
        static = [_on_the_way(rng, *spots[k]) for k in range(layout.static)]
        moving = [_crossing(rng, ball, goal, frac) for frac in (0.35, 0.7)[: layout.moving]]
        heading = 0.0
    elif layout.role == "defend":
        robot = np.array([rng.uniform(-7.0, -6.0), rng.uniform(-2.0, 2.0)])
        h0 = np.array([rng.uniform(1.5, 2.5), rng.uniform(-2.0, 2.0)])
        h1 = np.array([-7.5, rng.uniform(-0.5, 0.5)])
        speed = rng.uniform(0.5, 0.8)
        holder = MovingObstacle.scripted(PLAYER_RADIUS, np.stack((h0, h1)), speed=speed)
        ball = h0 + HOLD_DISTANCE * _unit(h1 - h0)
        # Where they would meet at full speed: the obstacles go on that way.
        gap = float(np.hypot(*(ball - robot)))
        meet = ball + speed * gap / (speed + 1.5) * _unit(h1 - h0)
        static = [_on_the_way(rng, robot, meet, 0.5) for _ in range(layout.static)]
        moving = [holder] + [_crossing(rng, robot, meet, frac) for frac in (0.35, 0.65)[
            : layout.moving]]  # fmt: skip
        heading = 0.0
    else:
        robot = np.array([rng.uniform(2.0, 3.0), rng.uniform(2.5, 3.5)])
        mate = np.array([rng.uniform(0.5, 1.5), rng.uniform(-2.0, 0.0)])
        ball = mate + np.array([HOLD_DISTANCE, 0.0])
        point = 0.5 * (ball + own)
        static = [_on_the_way(rng, robot, point, 0.5) for _ in range(layout.static)]
        moving = [_crossing(rng, robot, point, 0.3) for _ in range(layout.moving)]
        heading = math.pi
    static_xy = np.array(static, dtype=np.float64).reshape(-1, 2)
    solid = static_xy if mate is None else np.vstack((static_xy, mate[None, :]))
    world = field_world(solid, tuple(moving))
    return Game(layout, (float(robot[0]), float(robot[1]), heading), ball, static_xy,
                tuple(moving), holder, mate, world)  # fmt: skip


def player_attraction(max_speed: float) -> BlendedAttraction:
    """The robot's attraction: the paper's blend, the cone's gradient ``m`` its top speed.

    ``threshold_radius`` 0.5 m and width 0.15 m (navkit's defaults, free of the
    narrow-width ring of false minima), ``m = max_speed`` and
    ``K_att = max_speed / 0.75`` (2 at the default 1.5 m/s), so the paraboloid
    still pulls at 0.6 × the top speed where the ball is taken (0.45 m).
    """
    # K_att scales with m: a fixed K_att = 2 left the blend pulling outward just
    # beyond rad_thr for m <= 1.2 (a ring of false minima the robot stalls on,
    # outside the 0.45 m where the ball is taken); at K_att = m / 0.75 the pull
    # is inward by at least 5 % of m from 0.2 m to 3 m for every m in [0.2, 5].
    return BlendedAttraction(np.zeros(2), k_att=max_speed / 0.75, threshold_radius=0.5,
                             width=0.15, m=max_speed)  # fmt: skip


class Player:
    """The simulated robot's controller: role → goal and repellers → potential-field step.

    A plain class with ``__slots__``: it keeps the game's state (ball held,
    times, outcome) and the controller's between control steps. ``done``
    turns true when the role's task is over (scored, ball taken, support
    point reached) or the controller is stalled in a local minimum.
    """

    __slots__ = (
        "ctl",
        "done",
        "dt",
        "game",
        "has_ball",
        "noise",
        "outcome",
        "rng",
        "t_ball",
        "t_done",
    )

    def __init__(
        self,
        game: Game,
        *,
        max_speed: float,
        control_rate: float,
        noise: float,
        seed: int | np.random.SeedSequence,
    ) -> None:
        self.game = game
        self.ctl = PotentialFieldController(
            player_attraction(max_speed),
            k_rep=K_REP,
            influence_radius=INFLUENCE_RADIUS,
            max_speed=max_speed,
            max_accel=MAX_ACCEL,
            max_decel=MAX_DECEL,
            max_omega=4.0,
            kp=4.0,
            kd=0.1,
            goal_tolerance=SUPPORT_TOLERANCE,
            stall_radius=0.05,
            stall_timeout=2.0,
        )
        self.dt = 1.0 / control_rate
        self.noise = noise
        self.rng = np.random.default_rng(seed)
        self.has_ball = False
        self.done = False
        self.outcome = "running"
        self.t_ball = math.nan
        self.t_done = math.nan

    def _seen(self, xy: FloatArray) -> FloatArray:
        if self.noise == 0.0 or xy.size == 0:
            return xy
        out: FloatArray = xy + self.noise * self.rng.standard_normal(xy.shape)
        return out

    def _finish(self, t: float, outcome: str) -> Twist2D:
        self.done = True
        self.outcome = outcome
        self.t_done = t
        return Twist2D(0.0, 0.0, 0.0)

    def __call__(self, obs: Observation) -> Twist2D:
        game = self.game
        pose = obs.true_pose
        t = obs.t
        here = np.array([pose.x, pose.y])
        moving_xy = np.array([ob.position_at(t) for ob in game.opponents]).reshape(-1, 2)
        opponents = np.vstack((moving_xy, game.static_xy))
        role = game.layout.role
        holder: int | None = None
        if role == "attack":
            if not self.has_ball and math.hypot(*(game.ball_xy - here)) <= POSSESSION_RADIUS:
                self.has_ball = True
                self.t_ball = t
            if self.has_ball:
                ball = here + HOLD_DISTANCE * np.array([math.cos(pose.theta), math.sin(pose.theta)])
                if ball[0] >= OPPONENT_GOAL[0] and abs(ball[1]) < 0.5 * GOAL_WIDTH - BALL_RADIUS:
                    return self._finish(t, "scored")
            else:
                ball = game.ball_xy
        elif role == "defend":
            assert game.holder is not None
            h_now = game.holder.position_at(t)
            h_next = game.holder.position_at(t + 0.1)
            step = h_next - h_now
            direction = (
                _unit(step) if float(np.hypot(step[0], step[1])) > 1e-9
                else _unit(game.ball_xy - game.holder.position_at(0.0))
            )  # fmt: skip
            ball = h_now + HOLD_DISTANCE * direction
            holder = 0
            if math.hypot(*(ball - here)) <= POSSESSION_RADIUS:
                self.t_ball = t
                return self._finish(t, "ball taken")
        else:
            ball = game.ball_xy
        mates = np.empty((0, 2)) if game.mate_xy is None else game.mate_xy[None, :]
        state = GameState(
            robot_xy=here,
            ball_xy=self._seen(ball) if not self.has_ball else ball,
            teammates_xy=self._seen(mates),
            opponents_xy=self._seen(opponents),
            own_goal_xy=OWN_GOAL,
            opponent_goal_xy=OPPONENT_GOAL,
            has_ball=self.has_ball,
            opponent_with_ball=holder,
            possession_radius=POSSESSION_RADIUS,
        )
        target = attack(state) if role == "attack" else defend(state) if role == "defend" else (
            support(state))  # fmt: skip
        goal = target.goal_xy
        if role == "support" and math.hypot(*(goal - here)) <= SUPPORT_TOLERANCE:
            return self._finish(t, "in position")
        # Face the goal of the move; support faces the ball.
        look = ball if role == "support" else goal
        heading = math.atan2(look[1] - pose.y, look[0] - pose.x)
        # The time this command is held (3 or 4 physics steps at 30 Hz of 100 Hz), for
        # the controller's acceleration limits and stall clock.
        dt = self.dt if obs.dt is None else obs.dt
        cmd = self.ctl.step(pose, (float(goal[0]), float(goal[1]), heading), dt=dt,
                            obstacles=target.obstacles_xy)  # fmt: skip
        if self.ctl.stalled:
            return self._finish(t, "stalled")
        return cmd
