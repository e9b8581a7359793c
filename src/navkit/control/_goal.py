"""Private: whether a robot is at its goal position, the one test of every controller.

``PotentialFieldController`` (its ``done``), ``FollowTheCarrot``,
``OnOffTracker`` (its waypoints too) and ``RegulatedPurePursuit`` all decide
"within ``goal_tolerance``" here. They used ``np.hypot`` (the platform's libm)
and ``math.hypot`` (CPython's own), which may differ by an ulp: a robot one ulp
from the tolerance was at the goal for one controller and not for another.
"""

from __future__ import annotations

import math
from fractions import Fraction

__all__ = ["at_goal", "within"]

#: How far (in ulps of the tolerance) ``math.hypot`` may be from the true length
#: for the comparison to be decided by it: it is within one ulp of the length
#: (CPython's documented bound); beyond four, no rounding changes the answer.
_HYPOT_ULPS = 4.0


def within(dx: float, dy: float, tolerance: float) -> bool:
    """Whether the offset ``(dx, dy)`` (m, finite) is at most ``tolerance`` (m) long.

    Exactly: ``dx² + dy² <= tolerance²`` in rational arithmetic, so that the
    answer depends on no ``hypot`` implementation; computed so only within a
    few ulps of the boundary (about 2 µs there), by ``math.hypot`` elsewhere.

    Examples
    --------
    >>> within(3.0, 4.0, 5.0), within(0.5, 0.0, 0.5), within(0.5000000000000001, 0.0, 0.5)
    (True, True, False)

    The floats nearest 0.3 and 0.4 make an offset longer than 0.5 (by 2e-17 m),
    which ``math.hypot`` rounds to 0.5:

    >>> within(0.3, 0.4, 0.5), math.hypot(0.3, 0.4)
    (False, 0.5)
    """
    d = math.hypot(dx, dy)
    if not abs(d - tolerance) <= _HYPOT_ULPS * math.ulp(tolerance):
        return d < tolerance  # (a NaN offset, never passed, is not at the goal)
    fx, fy, ft = Fraction(dx), Fraction(dy), Fraction(tolerance)
    return fx * fx + fy * fy <= ft * ft


def resolution(x: float, y: float) -> float:
    """The float resolution (m) of world coordinates at the point ``(x, y)``: one ulp
    of the finer coordinate (the smaller in magnitude).

    A goal tolerance below it (1e-12 m at (4.6e6, 4.6e6) m, where it is 9.3e-10 m)
    is met only on the goal itself, which a differential robot's arcs did not land
    on: it turned in place and crept between two points one ulp beside the goal
    for ever, never done (review 38; every start of 20 tried). A goal that near
    counts as reached: no pose is nearer without being on it. Not the ulp of the
    larger coordinate: where the other is finer, nearer poses exist and are
    reached (1e-12 m at (4.6e6, 0.5) m was met within 1e-12 m), and that radius
    ended those runs 5e-10 to 8e-10 m away (review 38, REV38).

    Examples
    --------
    >>> resolution(4.6e6, 4.6e6), resolution(4.6e6, 0.5)
    (9.313225746154785e-10, 1.1102230246251565e-16)
    """
    return math.ulp(min(abs(x), abs(y)))


def at_goal(px: float, py: float, gx: float, gy: float, tolerance: float) -> bool:
    """Whether a robot at ``(px, py)`` has reached the goal ``(gx, gy)`` (m).

    :func:`within` ``tolerance`` of it (the offset ``goal - robot`` as floats),
    or within the coordinates' :func:`resolution` there.

    Examples
    --------
    >>> at_goal(1.0, 2.0, 1.0, 2.05, 0.05), at_goal(1.0, 2.0, 1.0, 2.0500001, 0.05)
    (True, False)
    """
    dx, dy = gx - px, gy - py
    return within(dx, dy, tolerance) or math.hypot(dx, dy) <= resolution(gx, gy)
