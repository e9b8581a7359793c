"""numba kernel advancing a simulation between two of its Python steps (private).

``run_segment`` runs the physics steps from step ``i0`` to step ``i_end``
(where the simulation's Python side next has work: a control step or a LiDAR
scan): at every step it samples the wheel encoders, compass and IMU when they
are due (exact values; Python adds noise), records the trace row
(time, pose, command) and, between steps, moves the robot
(:func:`navkit.sim._wheel_kernels.wheel_step`), places the moving obstacles,
measures the footprint's clearance (collision when 0) and checks the goal.

A step long for the footprint could carry it through a thin wall or wholly
into a solid obstacle, both out of contact at the step's end. So when the
step's ``span`` (a bound on how far any point of the footprint moves along
the step's arc: ``(|v| + |omega| * reach) * dt``, ``reach`` the footprint's
farthest point from the reference point, 0 for a disc) exceeds ``sweep`` (the
radius of a disc that fits inside the footprint) and the end is free, the
static obstacles are also checked at poses along the arc (the moving ones are
placed for the step's end only). From a pose with clearance ``c`` the next one
is ``max(c, sweep)`` further on (no point of the footprint moving farther):
nothing is met in between when ``c`` is the larger, and the footprints at two
poses ``sweep`` apart overlap (their inner discs do), so that no wall is
passed and no solid entered in between. The first pose found touching an
obstacle is the collision's, in place of the step's end.

Step ``i`` happens at ``t = i / rate`` (``rate`` the physics rate, Hz): the
time of the trace row, the sensor readings, the moving obstacles, the goal and
the collisions, correctly rounded (0.3 at step 3 of 10 Hz, where ``3 * dt`` is
0.30000000000000004). The physics integrates over ``dt = 1 / rate``.

A sensor ``s`` with ``rates[s] > 0`` takes its ``k``-th sample (k = 0, 1, ...)
at the first step ``i`` with ``i * dt + tol >= k / rates[s]``, ``tol`` the
larger of 1e-9 s and ``2**-50 * k / rates[s]`` (review 49). The roundings of
``i * dt`` (two) and ``k / rates[s]`` (one) come to about ``3 * 2**-53`` of the
time, and decimal rates' own to ``2 * 2**-53``: beyond about 1e6 s they
exceeded 1e-9 s, and a sample due at a step was taken one step late (physics at
0.0027 Hz, a compass at 0.0009 Hz: 407 of 9000 samples, 370 s late). Below
1.1e6 s the tolerance is 1e-9 s as before; at most 8.9e-9 s, it stays far below
a step (at least 1e-4 s);
``counts[s]`` holds the next ``k``. The schedules keep comparing ``i * dt``, as
:func:`due_step` does, so that the steps a sensor fires on stay those of
earlier releases; only the times reported changed to ``i / rate``.

Status codes returned with the step reached: ``REACHED`` (``i_end``),
``COLLIDED`` (a collision ended the run at that step), ``GOAL`` (the goal
was reached and ends the run) and ``GOAL_UNDECIDED``: the robot stopped on
the goal tolerance's band, where ``math.hypot`` cannot tell whether it is at
the goal (:func:`navkit._shared.goal.goal_verdict`, all the kernels compile of
the goal test); the caller decides with :func:`decide_goal` (the exact test,
in Python) and resumes the kernel at that step, whose samples and trace row
are not yet taken (review 49: compiled into the kernels, the exact test took
a sixth of a second of ``Simulation.run``'s first use). The position it
decided not at the goal is passed back in ``goal``; at that same position
the kernels go on without stopping (review 50: a robot parked on the band,
such as a controller stopped on the tolerance's circle, stopped them at
every step, each step twice as slow).

A run kernel first bounds the steps' spans over the segment (each wheel's
speed stays between its present one and its command, :func:`_long_steps`) and
checks the steps along their arc only when one may be long. That choice is
data, not an argument type: one compilation serves both (issue 17: a variant
per choice compiled each run kernel twice more, a few seconds in all, and the
checks' code in the loop, never run, costs a disc robot's steps nothing
measurable). Each run kernel is compiled once for a disc footprint (None for
the polygon's arrays, so that only the disc's distance code is compiled, see
:mod:`navkit.sim._clearance_kernels`) and once for a polygon.

``run_edge_segment`` is ``run_segment`` for a world of static segments and
circles only (no occupancy grid, no moving obstacles): it checks the
clearance with ``edge_clearance`` and places no obstacles, so that such a
world compiles neither the grid's nor the moving obstacles' code on first use.
The two share the work after the clearance check (``_settle``).

The arc is :mod:`navkit._shared.se2`'s and the goal test
:mod:`navkit._shared.goal`'s, inlined here: numba's cache keys these kernels on
this file alone, so a change of those helpers comes with a note here (review 49:
``sinc``'s series, now in Horner form below 2**-10, was below 1e-4; the run
kernels compile ``goal_verdict``, no longer the exact ``at_goal``; review 51:
``wrap_scalar`` and ``integrate_scalar`` are compiled once and inlined by LLVM).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from navkit._shared.goal import INSIDE, OUTSIDE, UNDECIDED, at_goal, goal_verdict_kernel
from navkit._shared.jit import bind_numba_names, njit_force_inline, njit_helper, njit_no_refcount
from navkit._shared.se2 import integrate_scalar, wrap_scalar
from navkit.sim._clearance_kernels import TOUCH, edge_clearance, footprint_clearance
from navkit.sim._moving_kernels import place_moving, point_in_moving
from navkit.sim._wheel_kernels import wheel_step

# numba's min and max builtins, without an overload compiled per argument types
# (navkit._shared.selects: intrinsics, so bound when numba loads; issue 17).
min2: Any = None
max2: Any = None
bind_numba_names(
    globals(), "navkit._shared.selects", python={"min2": min, "max2": max}, min2="min2", max2="max2"
)

__all__ = ["COLLIDED", "GOAL", "GOAL_UNDECIDED", "REACHED", "STAT_COLLISIONS",
           "STAT_IN_CONTACT", "STAT_MIN_CLEARANCE", "STAT_TIME_TO_GOAL", "decide_goal",
           "due_step", "run_edge_segment", "run_segment"]  # fmt: skip


REACHED = 0
COLLIDED = 1
GOAL = 2
GOAL_UNDECIDED = 3

#: Indices of the run statistics array.
STAT_MIN_CLEARANCE = 0
STAT_TIME_TO_GOAL = 1
STAT_COLLISIONS = 2
STAT_IN_CONTACT = 3
#: Values of ``stats[STAT_IN_CONTACT]``: free; touching at the last step; held
#: (put back after a contact and not moved since, so that pushing on from
#: there is the same collision).
_FREE = 0.0
_TOUCHING = 1.0
_HELD = 2.0

_EPS = 1e-9
#: The schedules' tolerance relative to the time, beyond ``_EPS / _REL`` = 1.1e6 s.
_REL = 2.0**-50
_TWO_PI = 2.0 * math.pi
#: Smallest limit of a step's clearance search, m: above ``TOUCH``, so that the
#: search still tells contact from no contact once the run's smallest clearance
#: (its limit otherwise) is 0, and small enough to stop the search at once.
_CONTACT_LIMIT = 1e-9
# Sensor slots of ``rates`` / ``counts`` / ``n_out``.
_ENCODERS = 0
_COMPASS = 1
_IMU = 2


def due_step(k: int, rate: float, dt: float) -> int:
    """First step ``i`` with ``i * dt + tol >= k / rate``, ``tol`` = max(1e-9, 2**-50 k / rate).

    Plain Python (called from Python a few times per control step): the same
    IEEE operations as a kernel would do, without a kernel's compilation.
    """
    when = k / rate
    tol = max(_EPS, _REL * when)
    i = max(math.ceil((when - tol) / dt) - 1, 0)
    while i * dt + tol < when:
        i += 1
    return i


def decide_goal(
    i: int,
    rate: float,
    state: np.ndarray,
    goal: np.ndarray,
    stop_at_goal: bool,
    stats: np.ndarray,
    times: np.ndarray,
    poses: np.ndarray,
    commands: np.ndarray,
    cmd: np.ndarray,
) -> bool:
    """Decide the goal at step ``i``, where a run kernel returned ``GOAL_UNDECIDED``.

    The position by :func:`~navkit._shared.goal.at_goal` (the heading passed
    in the kernel). If it is at the goal, notes the step's time
    (``stats[STAT_TIME_TO_GOAL]``) and, with ``stop_at_goal``, writes the
    step's trace row as the kernel does and returns True: the run ends there
    (``GOAL``). Otherwise returns False: the caller runs the kernel on from
    step ``i`` with ``sample_first`` (the step's samples and row, then the
    rest of the segment, with the slip draws from step ``i``'s on). A position
    not at the goal is kept in ``goal[5:7]``: the kernels answer it themselves
    while the robot stays there (review 50: a robot parked on the band stopped
    the kernel at every step).
    Plain Python, called for steps on the tolerance's band only.
    """
    if not at_goal(float(state[0]), float(state[1]), float(goal[0]), float(goal[1]),
                   float(goal[2])):  # fmt: skip
        # Remembered for the kernels: while the robot stays at this position (parked on
        # the band), they answer "not at the goal" themselves.
        goal[5] = state[0]
        goal[6] = state[1]
        return False
    t = i / rate
    stats[STAT_TIME_TO_GOAL] = t
    if not stop_at_goal:
        return False
    times[i] = t
    poses[i, :3] = state[:3]
    commands[i, :3] = cmd[:3]
    return True


@njit_helper
def _sample(
    i: int,
    t: float,
    dt: float,
    state: np.ndarray,
    angles: np.ndarray,
    rates: np.ndarray,
    counts: np.ndarray,
    n_out: np.ndarray,
    enc_tpr: float,
    enc_span: float,
    enc_out: np.ndarray,
    compass_out: np.ndarray,
    imu_out: np.ndarray,
) -> None:
    for s in range(3):
        if rates[s] <= 0.0:
            continue
        when = counts[s] / rates[s]
        if i * dt + max2(_EPS, _REL * when) < when:
            continue
        counts[s] += 1
        row = n_out[s]
        n_out[s] = row + 1
        if s == _ENCODERS:
            enc_out[row, 0] = t
            for w in range(angles.shape[0]):
                # The tick rule of WheelEncoders.counts, in the same float arithmetic.
                a = angles[w]
                ticks = np.floor(a * (enc_tpr / _TWO_PI))
                if ((ticks + 1.0) / enc_tpr) * _TWO_PI <= a:
                    ticks += 1.0
                elif (ticks / enc_tpr) * _TWO_PI > a:
                    ticks -= 1.0
                if enc_span > 0.0:
                    ticks = ticks % enc_span
                enc_out[row, 1 + w] = ticks
        elif s == _COMPASS:
            compass_out[row, 0] = t
            compass_out[row, 1] = state[2]
        else:
            imu_out[row, 0] = t
            imu_out[row, 1] = state[5]
            imu_out[row, 2] = state[6]
            imu_out[row, 3] = state[7]


@njit_helper
def _record(
    times: np.ndarray,
    poses: np.ndarray,
    commands: np.ndarray,
    i: int,
    t: float,
    state: np.ndarray,
    cmd: np.ndarray,
) -> None:
    # One array per trace column group, grown and trimmed in place: the trace
    # adopts them without a copy.
    times[i] = t
    poses[i, 0] = state[0]
    poses[i, 1] = state[1]
    poses[i, 2] = state[2]
    commands[i, 0] = cmd[0]
    commands[i, 1] = cmd[1]
    commands[i, 2] = cmd[2]


@njit_helper
def _inside_moving(
    px: float,
    py: float,
    verts: np.ndarray | None,
    dyn_segs: np.ndarray,
    dyn_seg_owner: np.ndarray,
    dyn_circles: np.ndarray,
) -> bool:
    """Whether a footprint that touches no boundary lies inside a moving obstacle.

    Such a footprint is wholly inside or wholly outside each obstacle (all
    solid), so one of its points decides: the disc's centre ``(px, py)``, or
    the first vertex of the placed polygon ``verts``.
    """
    if verts is not None:
        px = verts[0, 0]
        py = verts[0, 1]
    return point_in_moving(px, py, dyn_segs, dyn_seg_owner, dyn_circles)


@njit_helper
def _long_steps(
    wheels: np.ndarray,
    command: np.ndarray,
    radius_factor: np.ndarray,
    fwd: np.ndarray,
    reach: float,
    dt: float,
    sweep: float,
) -> bool:
    """Whether a step of this segment may be long: its ``span`` above ``sweep``.

    Until the next control step every wheel's speed stays between its present
    one and its command (it ramps toward the command; a collision stops it), and
    slip only slows its ground speed; so ``|fwd[k]| . max(|wheel|, |command|) *
    radius_factor`` bounds each twist component over the segment.
    """
    vx = 0.0
    vy = 0.0
    om = 0.0
    for w in range(wheels.shape[0]):
        top = max2(abs(wheels[w]), abs(command[w])) * radius_factor[w]
        vx += abs(fwd[0, w]) * top
        vy += abs(fwd[1, w]) * top
        om += abs(fwd[2, w]) * top
    long: bool = (vx + vy + om * reach) * dt > sweep
    return long


@njit_helper
def _sweep_static(
    state: np.ndarray,
    prev: np.ndarray,
    dt: float,
    reach: float,
    sweep: float,
    radius: float,
    body_verts: np.ndarray | None,
    verts: np.ndarray | None,
    scratch: np.ndarray | None,
    segs: np.ndarray,
    circles: np.ndarray,
    gx0: float,
    gy0: float,
    h: float,
    nx: int,
    ny: int,
    cell_start: np.ndarray,
    cell_items: np.ndarray,
    occ: np.ndarray | None,
    gox: float,
    goy: float,
    gcos: float,
    gsin: float,
    res: float,
    dyn_segs: np.ndarray | None,
    dyn_circles: np.ndarray | None,
    edges: bool | None,
) -> bool:
    """Whether the footprint touches a static obstacle along the step from ``prev``.

    Checks poses along the step's arc as the module's docstring says; on
    contact the pose in ``state`` becomes the first one touching. ``edges``
    is True in a world of static segments and circles only (numba then
    compiles :func:`edge_clearance` alone, as ``run_edge_segment`` does;
    ``occ``, ``dyn_segs`` and ``dyn_circles`` are None), else None: ``occ`` is
    the occupancy grid, whose cells count too, and ``dyn_segs`` and
    ``dyn_circles`` the moving obstacles' arrays, of which only empty views
    are used. The kind of world is told by ``edges is not None`` because numba
    decides a test ``x is None`` before typing only where ``x`` is None: a test
    of ``occ is None`` left the branch for a world without a grid in the grid's
    variants, which then compiled :func:`edge_clearance` and linked its code
    into both footprints' ``run_segment`` (review 52: a disc robot in a grid
    world compiled a kernel it never ran).
    """
    # A bound on the distance any point of the footprint moved over the step, m (not
    # a helper of its own: compiling one costs a tenth of a second on first use).
    span = (math.hypot(state[3], state[4]) + abs(state[5]) * reach) * dt
    if not sweep < span < math.inf:
        return False
    vx = state[3]
    vy = state[4]
    om = state[5]
    done = 0.0
    while True:
        x, y, th = integrate_scalar(prev[0], prev[1], prev[2], vx, vy, om, done / span * dt)
        rest = span - done
        limit = max2(rest, _CONTACT_LIMIT)
        if edges is not None:
            c = edge_clearance(
                x, y, th, radius, body_verts, verts, segs, circles, gx0, gy0, h, nx, ny,
                cell_start, cell_items, limit,
            )  # fmt: skip
        elif occ is not None and dyn_segs is not None and dyn_circles is not None:
            # Without the moving obstacles (empty views of their arrays, so that the
            # kernel's one signature serves): their placement holds at the step's end only.
            c = footprint_clearance(
                x, y, th, radius, body_verts, verts, scratch, segs, circles, gx0, gy0, h, nx,
                ny, cell_start, cell_items, occ, gox, goy, gcos, gsin, res, dyn_segs[:0],
                dyn_circles[:0], limit,
            )  # fmt: skip
        else:  # not reached: the grid and the moving obstacles' arrays come together
            c = 0.0
        if c <= TOUCH:
            state[0] = x
            state[1] = y
            state[2] = th
            return True
        advance = max2(c, sweep)
        if advance >= rest:
            return False
        done += advance


# Compiled once and inlined by LLVM into both run kernels: left a call (LLVM finds it too
# big to inline), it made the physics loop a few per cent slower.
@njit_force_inline
def _settle(
    i: int,
    t: float,
    dt: float,
    clearance: float,
    state: np.ndarray,
    wheels: np.ndarray,
    angles: np.ndarray,
    command: np.ndarray,
    goal: np.ndarray,
    stop_at_goal: bool,
    end_on_collision: bool,
    rates: np.ndarray,
    counts: np.ndarray,
    n_out: np.ndarray,
    enc_tpr: float,
    enc_span: float,
    enc_out: np.ndarray,
    compass_out: np.ndarray,
    imu_out: np.ndarray,
    times: np.ndarray,
    poses: np.ndarray,
    commands: np.ndarray,
    cmd: np.ndarray,
    stats: np.ndarray,
    contacts: np.ndarray,
    prev: np.ndarray,
) -> int:
    """Finish the step that reached step ``i`` with the footprint's ``clearance``.

    Stops the robot on contact (back at ``prev`` unless the run ends), records
    the goal and samples the sensors; returns ``REACHED`` to go on, otherwise
    the status that ends the segment (the trace row is written either way but
    for ``GOAL_UNDECIDED``, which leaves the step's samples and row to the
    kernel's resumption, :func:`decide_goal`).
    """
    if clearance <= TOUCH:
        clearance = 0.0  # touching: the few 1e-17 m left are rounding
    if clearance < stats[STAT_MIN_CLEARANCE]:
        stats[STAT_MIN_CLEARANCE] = clearance
    # Whether the robot moved over this step (a stopped robot's twist is exactly 0).
    moved = state[3] != 0.0 or state[4] != 0.0 or state[5] != 0.0
    contact = stats[STAT_IN_CONTACT]
    if clearance <= 0.0:
        # A new collision, unless the contact goes on or a held robot pushes on
        # (an obstacle reaching a held robot that stands still is a new one).
        if contact == _FREE or (contact == _HELD and not moved):
            n = np.int64(stats[STAT_COLLISIONS])  # not int(): an overload to compile
            if n < contacts.shape[0]:
                contacts[n] = t
            stats[STAT_COLLISIONS] = n + 1
        stats[STAT_IN_CONTACT] = _TOUCHING
        # Every wheel stops at once and stays stopped until the next control step;
        # ``cmd``, the controller's latest output that the trace records, stands.
        for w in range(wheels.shape[0]):
            wheels[w] = 0.0
            command[w] = 0.0
        for k in range(3, 8):
            state[k] = 0.0
        if end_on_collision:
            _record(times, poses, commands, i, t, state, cmd)
            return COLLIDED
        state[0] = prev[0]
        state[1] = prev[1]
        state[2] = prev[2]
    elif moved or contact == _FREE:
        stats[STAT_IN_CONTACT] = _FREE
    else:
        stats[STAT_IN_CONTACT] = _HELD
    # The goal, first reached? ``goal`` = [x, y, radius, yaw, yaw tolerance, x, y of the
    # position last decided not at it in Python]; NaN x for no goal, NaN yaw for any
    # heading, NaN x, y for none decided. (Not a helper of its own: each separately
    # compiled function costs a tenth of a second or more on first use; wrap_scalar,
    # compiled once since review 51, is inlined here by LLVM.) The position by the
    # controllers' own exact test (review 48:
    # math.hypot counted offsets on the radius's last ulp as reached where the
    # controller was not done, or the reverse; a NaN offset is never at the goal:
    # review 48, FRESH), its band around the radius left to Python (review 49).
    if math.isnan(stats[STAT_TIME_TO_GOAL]) and not math.isnan(goal[0]):
        verdict = goal_verdict_kernel(state[0], state[1], goal[0], goal[1], goal[2])
        if (
            verdict != OUTSIDE
            and not math.isnan(goal[3])
            and not abs(wrap_scalar(state[2] - goal[3])) <= goal[4]
        ):
            verdict = OUTSIDE
        if verdict == UNDECIDED:
            if state[0] != goal[5] or state[1] != goal[6]:
                return GOAL_UNDECIDED
            # The position Python last decided not at the goal (decide_goal, goal[5:7]):
            # the same answer, without stopping for it again (at_goal depends on the
            # position alone, and alike for 0.0 and -0.0, which compare equal). A robot
            # parked on the band handed every step to Python, twice as slow (review 50).
            verdict = OUTSIDE
        if verdict == INSIDE:
            stats[STAT_TIME_TO_GOAL] = t
            if stop_at_goal:
                _record(times, poses, commands, i, t, state, cmd)
                return GOAL
    _sample(
        i, t, dt, state, angles, rates, counts, n_out, enc_tpr, enc_span,
        enc_out, compass_out, imu_out,
    )  # fmt: skip
    _record(times, poses, commands, i, t, state, cmd)
    return REACHED


@njit_no_refcount
def run_segment(
    i0: int,
    i_end: int,
    rate: float,
    sample_first: bool,
    state: np.ndarray,
    wheels: np.ndarray,
    angles: np.ndarray,
    carry: np.ndarray,
    command: np.ndarray,
    max_accel: float,
    radius_factor: np.ndarray,
    slip: float,
    slip_z: np.ndarray,
    fwd: np.ndarray,
    radius: float,
    reach: float,
    sweep: float,
    body_verts: np.ndarray | None,
    verts: np.ndarray | None,
    segs: np.ndarray,
    circles: np.ndarray,
    gx0: float,
    gy0: float,
    h: float,
    nx: int,
    ny: int,
    cell_start: np.ndarray,
    cell_items: np.ndarray,
    scratch: np.ndarray | None,
    occ: np.ndarray,
    gox: float,
    goy: float,
    gcos: float,
    gsin: float,
    res: float,
    mv_path: np.ndarray,
    mv_times: np.ndarray,
    mv_first: np.ndarray,
    mv_count: np.ndarray,
    mv_after: np.ndarray,
    dyn_base_segs: np.ndarray,
    dyn_seg_owner: np.ndarray,
    dyn_segs: np.ndarray,
    dyn_base_circles: np.ndarray,
    dyn_circle_owner: np.ndarray,
    dyn_circles: np.ndarray,
    goal: np.ndarray,
    stop_at_goal: bool,
    end_on_collision: bool,
    rates: np.ndarray,
    counts: np.ndarray,
    n_out: np.ndarray,
    enc_tpr: float,
    enc_span: float,
    enc_out: np.ndarray,
    compass_out: np.ndarray,
    imu_out: np.ndarray,
    times: np.ndarray,
    poses: np.ndarray,
    commands: np.ndarray,
    cmd: np.ndarray,
    stats: np.ndarray,
    contacts: np.ndarray,
    prev: np.ndarray,
) -> tuple[int, int]:
    """Advance from step ``i0`` to step ``i_end``; returns ``(status, step reached)``.

    ``rate`` is the physics rate, Hz: steps of ``1 / rate`` s, step ``i`` at
    ``i / rate`` s.
    ``slip_z`` holds the slip draws, row ``k`` for the physics step leaving
    step ``i0 + k``. ``n_out`` (3,) counts the rows written to ``enc_out``
    (t, then each wheel's counter ``floor(angle / 2π * enc_tpr)`` by the rule of
    ``WheelEncoders.counts``, modulo ``enc_span`` when it is > 0), ``compass_out``
    (t, yaw) and ``imu_out`` (t, yaw rate, ax, ay). ``stats`` holds the minimum
    clearance, the time the goal was first reached (NaN before), the number of
    collisions and the robot's contact state (free, touching or held); the times
    of the collisions are appended to ``contacts`` (as far as it has room;
    ``stats[STAT_COLLISIONS]`` counts them all).
    ``carry`` holds the compensation of the wheel angles' sums (see
    :func:`~navkit.sim._wheel_kernels.wheel_step`), kept from segment to
    segment. ``prev`` (3,) is scratch for the pose before a step. ``reach`` (m) is the
    footprint's farthest point from the robot's reference point (0 for a
    disc) and ``sweep`` (m, > 0) the radius of a disc inside it.
    ``body_verts``, ``verts`` and ``scratch`` are None for a disc footprint.
    """
    has_moving = mv_first.shape[0] > 0
    dt = 1.0 / rate
    # Whether a step may be long: then every step is checked along its arc.
    check_arcs = _long_steps(wheels, command, radius_factor, fwd, reach, dt, sweep)
    i = i0
    if sample_first:
        _sample(
            i, i / rate, dt, state, angles, rates, counts, n_out, enc_tpr, enc_span,
            enc_out, compass_out, imu_out,
        )  # fmt: skip
        _record(times, poses, commands, i, i / rate, state, cmd)
    while i < i_end:
        prev[0] = state[0]
        prev[1] = state[1]
        prev[2] = state[2]
        wheel_step(
            state, wheels, angles, carry, command, max_accel, dt, radius_factor,
            slip_z[i - i0], slip, fwd,
        )  # fmt: skip
        i += 1
        t = i / rate
        if has_moving:
            place_moving(
                t, mv_path, mv_times, mv_first, mv_count, mv_after,
                dyn_base_segs, dyn_seg_owner, dyn_segs,
                dyn_base_circles, dyn_circle_owner, dyn_circles,
            )  # fmt: skip
        clearance = footprint_clearance(
            state[0], state[1], state[2], radius, body_verts, verts, scratch,
            segs, circles, gx0, gy0, h, nx, ny, cell_start, cell_items,
            occ, gox, goy, gcos, gsin, res, dyn_segs, dyn_circles,
            max2(stats[STAT_MIN_CLEARANCE], _CONTACT_LIMIT),
        )  # fmt: skip
        # A moving obstacle may have swept over the robot: inside it is a contact too.
        if (
            clearance > TOUCH and has_moving
            and _inside_moving(state[0], state[1], verts, dyn_segs, dyn_seg_owner, dyn_circles)
        ):  # fmt: skip
            clearance = 0.0
        # A long step may have passed through a wall or into a solid.
        if check_arcs and clearance > TOUCH and _sweep_static(
            state, prev, dt, reach, sweep, radius, body_verts, verts, scratch, segs,
            circles, gx0, gy0, h, nx, ny, cell_start, cell_items, occ, gox, goy, gcos,
            gsin, res, dyn_segs, dyn_circles, None,
        ):  # fmt: skip
            clearance = 0.0
        status = _settle(
            i, t, dt, clearance, state, wheels, angles, command, goal, stop_at_goal,
            end_on_collision, rates, counts, n_out, enc_tpr, enc_span, enc_out,
            compass_out, imu_out, times, poses, commands, cmd, stats, contacts, prev,
        )  # fmt: skip
        if status != REACHED:
            return status, i
    return REACHED, i


@njit_no_refcount
def run_edge_segment(
    i0: int,
    i_end: int,
    rate: float,
    sample_first: bool,
    state: np.ndarray,
    wheels: np.ndarray,
    angles: np.ndarray,
    carry: np.ndarray,
    command: np.ndarray,
    max_accel: float,
    radius_factor: np.ndarray,
    slip: float,
    slip_z: np.ndarray,
    fwd: np.ndarray,
    radius: float,
    reach: float,
    sweep: float,
    body_verts: np.ndarray | None,
    verts: np.ndarray | None,
    segs: np.ndarray,
    circles: np.ndarray,
    gx0: float,
    gy0: float,
    h: float,
    nx: int,
    ny: int,
    cell_start: np.ndarray,
    cell_items: np.ndarray,
    goal: np.ndarray,
    stop_at_goal: bool,
    end_on_collision: bool,
    rates: np.ndarray,
    counts: np.ndarray,
    n_out: np.ndarray,
    enc_tpr: float,
    enc_span: float,
    enc_out: np.ndarray,
    compass_out: np.ndarray,
    imu_out: np.ndarray,
    times: np.ndarray,
    poses: np.ndarray,
    commands: np.ndarray,
    cmd: np.ndarray,
    stats: np.ndarray,
    contacts: np.ndarray,
    prev: np.ndarray,
) -> tuple[int, int]:
    """:func:`run_segment` in a world of static segments and circles only.

    The same steps as :func:`run_segment` given no occupancy grid and no moving
    obstacles (its arguments without theirs), checking the clearance with
    :func:`~navkit.sim._clearance_kernels.edge_clearance`.
    ``body_verts`` and ``verts`` are None for a disc footprint.
    """
    dt = 1.0 / rate
    # Whether a step may be long: then every step is checked along its arc.
    check_arcs = _long_steps(wheels, command, radius_factor, fwd, reach, dt, sweep)
    i = i0
    if sample_first:
        _sample(
            i, i / rate, dt, state, angles, rates, counts, n_out, enc_tpr, enc_span,
            enc_out, compass_out, imu_out,
        )  # fmt: skip
        _record(times, poses, commands, i, i / rate, state, cmd)
    while i < i_end:
        prev[0] = state[0]
        prev[1] = state[1]
        prev[2] = state[2]
        wheel_step(
            state, wheels, angles, carry, command, max_accel, dt, radius_factor,
            slip_z[i - i0], slip, fwd,
        )  # fmt: skip
        i += 1
        t = i / rate
        clearance = edge_clearance(
            state[0], state[1], state[2], radius, body_verts, verts,
            segs, circles, gx0, gy0, h, nx, ny, cell_start, cell_items,
            max2(stats[STAT_MIN_CLEARANCE], _CONTACT_LIMIT),
        )  # fmt: skip
        # A long step may have passed through a wall or into a solid.
        if check_arcs and clearance > TOUCH and _sweep_static(
            state, prev, dt, reach, sweep, radius, body_verts, verts, None, segs, circles,
            gx0, gy0, h, nx, ny, cell_start, cell_items, None, 0.0, 0.0, 0.0, 0.0, 0.0,
            None, None, True,
        ):  # fmt: skip
            clearance = 0.0
        status = _settle(
            i, t, dt, clearance, state, wheels, angles, command, goal, stop_at_goal,
            end_on_collision, rates, counts, n_out, enc_tpr, enc_span, enc_out,
            compass_out, imu_out, times, poses, commands, cmd, stats, contacts, prev,
        )  # fmt: skip
        if status != REACHED:
            return status, i
    return REACHED, i
