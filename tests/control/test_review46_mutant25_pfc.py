"""Review 46 (MUTANT25): mutants of PotentialFieldController's arrival left alive.

Review 46 made the controller :attr:`~PotentialFieldController.done` within
``goal_tolerance`` of its target (a differential drive then turns to the target
heading) and moved the arrival test out of the stall clock. Of 33 hand-made
mutants of those lines, four passed every earlier test and are killed here:

* ``to_goal < goal_tolerance`` for ``<=``: a robot exactly ``goal_tolerance``
  off its goal is done (and a diff drive there turns to the target heading);
* ``goal_tolerance`` for ``stall_radius`` in the stall clock (the defaults are
  both 0.05 m, so only different values tell them apart);
* ``steer = not arrived`` (dropping ``moving``): far from the goal a field
  under a thousandth of ``max_speed`` gives the target heading, not its
  direction;
* ``arrived = arrived or not moving``: such a weak field is no arrival (the
  robot there is not done, and it can stall).

The neighbouring mutants the earlier tests kill (half or twice the tolerance,
the Manhattan distance, ``stall_radius`` for ``goal_tolerance``, an arrival that
keeps the stall clock's time or anchor, arrival for a diff drive only) are
checked here too, with other values.

Oracle: the distance to the goal in exact rational arithmetic
(:class:`fractions.Fraction`), never the controller's own ``np.hypot``; the goal
is the origin, so the offsets are the poses' coordinates exactly.
"""

from __future__ import annotations

import math
from fractions import Fraction

import pytest

from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D

DT = 0.1


def _within(offset: tuple[float, float], tolerance: float) -> bool:
    """Whether ``offset`` is within ``tolerance``, exactly (squares of the floats as rationals)."""
    dx, dy = (Fraction(v) for v in offset)
    return dx * dx + dy * dy <= Fraction(tolerance) ** 2


def _done(ctl: PotentialFieldController) -> bool:
    """``ctl.done``, read afresh (mypy would narrow the property between steps)."""
    return ctl.done


def _stalled(ctl: PotentialFieldController) -> bool:
    """``ctl.stalled``, read afresh (as :func:`_done`)."""
    return ctl.stalled


@pytest.mark.parametrize("drive", ["diff", "omni"])
@pytest.mark.parametrize("tolerance", [0.005, 0.05, 0.375])
def test_done_is_within_goal_tolerance_boundary_included(drive: str, tolerance: float) -> None:
    goal = Pose2D(0.0, 0.0, 0.5)
    # Along each axis (exact offsets: the goal is the origin), just beyond, inside,
    # beyond by half or by twice, and diagonals inside by the Euclidean distance
    # but not by the sum of the offsets.
    up = math.nextafter(tolerance, math.inf)
    offsets = [
        (tolerance, 0.0),
        (0.0, -tolerance),
        (-tolerance, 0.0),
        (up, 0.0),
        (0.0, -up),
        (0.5 * tolerance, 0.0),
        (0.6 * tolerance, 0.6 * tolerance),
        (-0.7 * tolerance, 0.7 * tolerance),
        (1.5 * tolerance, 0.0),
        (0.0, 2.0 * tolerance),
        (0.0, 0.0),
    ]
    for dx, dy in offsets:
        ctl = PotentialFieldController(drive=drive, goal_tolerance=tolerance)  # type: ignore[arg-type]
        ctl.step(Pose2D(dx, dy, 0.0), goal, DT)
        assert _done(ctl) == _within((dx, dy), tolerance), (dx, dy)


@pytest.mark.parametrize("tolerance", [0.01, 0.05, 0.375])
def test_at_exactly_goal_tolerance_a_diff_drive_turns_to_the_target_heading(
    tolerance: float,
) -> None:
    # The default blend pulls towards the goal there: the field's direction is the
    # goal's bearing (0 here, the robot's heading); the target heading is 1 rad.
    goal = Pose2D(tolerance, 0.0, 1.0)
    assert _within((goal.x, 0.0), tolerance)
    ctl = PotentialFieldController(drive="diff", goal_tolerance=tolerance)
    cmd = ctl.step(Pose2D(0.0, 0.0, 0.0), goal, DT)
    assert _done(ctl)
    assert cmd.omega > 0.0  # towards +1 rad, not the bearing's 0 (no turn)
    beyond = Pose2D(math.nextafter(tolerance, math.inf), 0.0, 1.0)
    ctl = PotentialFieldController(drive="diff", goal_tolerance=tolerance)
    cmd = ctl.step(Pose2D(0.0, 0.0, 0.0), beyond, DT)
    assert not _done(ctl)
    assert cmd.omega == 0.0  # steers by the field: straight ahead


@pytest.mark.parametrize(("tolerance", "radius"), [(0.02, 0.2), (0.2, 0.02)])
def test_arrival_and_the_stall_clock_keep_their_own_distances(
    tolerance: float, radius: float
) -> None:
    goal = Pose2D(3.0, 0.0, 0.0)
    # 0.1 m from the goal: done only for the larger goal_tolerance.
    ctl = PotentialFieldController(goal_tolerance=tolerance, stall_radius=radius)
    ctl.step(Pose2D(2.9, 0.0, 0.0), goal, DT)
    assert _done(ctl) == (tolerance > 0.1)
    # Far from the goal, creeping 0.01 m a step (poses fed, not integrated): within
    # 0.2 m of the first spot for the whole timeout, out of 0.02 m every other step.
    ctl = PotentialFieldController(goal_tolerance=tolerance, stall_radius=radius, stall_timeout=0.5)
    for k in range(8):
        ctl.step(Pose2D(0.01 * k, 0.0, 0.0), goal, DT)
    assert ctl.stalled == (radius > 0.1)
    assert not _done(ctl)


def test_arriving_clears_the_stall_clock() -> None:
    goal = Pose2D(2.0, 0.0, 0.0)
    stuck = Pose2D(0.0, 0.0, 0.0)
    ctl = PotentialFieldController(stall_timeout=2.0)
    for _ in range(20):  # held 2 m off for 1.9 s: not yet stalled
        ctl.step(stuck, goal, DT)
    assert ctl.stall_time == pytest.approx(1.9) and not ctl.stalled
    # One step at the goal: done, the clock and its anchor gone.
    ctl.step(Pose2D(2.0, 0.01, 0.0), goal, DT)
    assert _done(ctl) and ctl.stall_time == 0.0 and not ctl.stalled
    # Back at the old spot the clock starts again, from a new anchor: a tenth of a
    # second later it reads 0.1 s, not the 2 s of the time before the arrival.
    ctl.step(stuck, goal, DT)
    assert not _done(ctl) and ctl.stall_time == 0.0
    ctl.step(stuck, goal, DT)
    assert ctl.stall_time == pytest.approx(DT) and not ctl.stalled


def test_a_stalled_robot_that_reaches_its_goal_is_done_not_stalled() -> None:
    goal = Pose2D(2.0, 0.0, 0.0)
    ctl = PotentialFieldController(stall_timeout=0.5)
    for _ in range(8):
        ctl.step((0.0, 0.0, 0.0), goal, DT)
    assert ctl.stalled
    ctl.step((2.0, 0.0, 0.0), goal, DT)  # moved there by hand (a teleop, say)
    assert _done(ctl) and not _stalled(ctl) and ctl.stall_time == 0.0


def test_an_omni_robot_at_its_goal_turns_by_the_target_heading_and_is_done() -> None:
    ctl = PotentialFieldController(drive="omni")
    cmd = ctl.step(Pose2D(2.0, 0.01, 0.0), Pose2D(2.0, 0.0, -1.0), DT)
    assert _done(ctl)
    assert cmd.omega < 0.0  # towards -1 rad


def test_far_from_the_goal_a_field_too_weak_to_steer_by_gives_the_target_heading() -> None:
    # 2 m from the goal, a paraboloid of gain 1e-6 asks for 4e-6 m/s, under a
    # thousandth of max_speed: the field's direction (the goal's bearing, +y) is
    # noise there, so a diff drive turns to the target heading (-1 rad), arrived
    # or not; it is not done.
    from navkit.planning import ParaboloidAttraction

    ctl = PotentialFieldController(ParaboloidAttraction((0.0, 0.0), k_att=1e-6), drive="diff")
    cmd = ctl.step(Pose2D(0.0, 0.0, 0.0), Pose2D(0.0, 2.0, -1.0), DT)
    assert not _done(ctl)
    assert cmd.omega < 0.0
    # Held there (a local minimum, for all the controller knows) it stalls.
    weak = PotentialFieldController(
        ParaboloidAttraction((0.0, 0.0), k_att=1e-6), drive="diff", stall_timeout=0.5
    )
    for _ in range(8):
        weak.step(Pose2D(0.0, 0.0, 0.0), Pose2D(0.0, 2.0, -1.0), DT)
    assert weak.stalled and not _done(weak)
    # With a gain that pulls, the same robot steers by the field: to +y.
    ctl = PotentialFieldController(ParaboloidAttraction((0.0, 0.0)), drive="diff")
    cmd = ctl.step(Pose2D(0.0, 0.0, 0.0), Pose2D(0.0, 2.0, -1.0), DT)
    assert cmd.omega > 0.0
