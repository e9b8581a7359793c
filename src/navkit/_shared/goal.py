"""Whether a robot is at its goal position: the controllers' test and the simulator's (private).

``PotentialFieldController`` (its ``done``), ``FollowTheCarrot``,
``OnOffTracker`` (its waypoints too) and ``RegulatedPurePursuit`` decide
"within ``goal_tolerance``" with :func:`at_goal`, and so does
:class:`~navkit.sim.Simulation` for "goal reached". Review 47 made the
controllers' test exact; the run kernel still compared numba's ``math.hypot``
(libm's) with the tolerance, which rounds an offset a hair beyond the
tolerance onto it: of offsets computed onto the tolerance's circle
(``t cos a, t sin a``), 42 % were misjudged so (review 48), and a robot standing
on one was "goal reached" for the run while its controller was not done.

:func:`at_goal` asks :func:`goal_verdict` first: ``math.hypot`` decides every
offset more than 2**-48 (relative) from the tolerance's circle. Only on that
band is the exact arithmetic needed (Dekker's products, Shewchuk's
Grow-Expansion, Rump's "unit in the first place" for ``math.ulp``). The run
kernels compile :func:`goal_verdict` alone (:data:`goal_verdict_kernel`) and
stop on an undecided step, where Python decides with :func:`at_goal` and
resumes them (:func:`navkit.sim._segment_kernels.decide_goal`). Compiled into
them, the exact arithmetic (and the scaling and resolution it needs) took a
sixth to a fifth of a second of ``Simulation.run``'s first use, for a band no
robot's path crosses but by design (issue 17: 3.20 s of CPU with a cold cache,
over its 3 s; 3.00 s without it, medians of six alternating runs on a busy
machine, review 49). numba's cache
keys the run kernels on ``navkit/sim/_segment_kernels.py`` alone: a change of
:func:`goal_verdict` must come with a change of that file, or a cache made
before it keeps running the old test there.
"""

from __future__ import annotations

import math

from navkit._shared.jit import njit_force_inline

__all__ = ["INSIDE", "OUTSIDE", "UNDECIDED", "at_goal", "goal_verdict", "goal_verdict_kernel",
           "resolution"]  # fmt: skip

#: 2**27 + 1: Veltkamp's constant, splitting a float into two halves of 26 bits
#: whose products are exact (Dekker's exact product).
_SPLIT = 134217729.0
#: How far (relative to the tolerance) ``hypot`` may be from the true length for
#: the comparison to be decided by it: within one ulp (2**-52 relative) of it on
#: CPython and libm alike; beyond 2**-48, no rounding changes the answer.
_HYPOT_MARGIN = 2.0**-48
#: Below this (relative to the tolerance) the offset's shorter side, squared, is
#: less than any nonzero gap between the tolerance's square and the longer side's.
_TINY_SIDE = 2.0**-60
#: 2**-52: no float's ulp exceeds it times the float.
_EPSILON = 2.0**-52
#: 2**52 + 1: Rump's factor for a float's leading power of two.
_PHI = 4503599627370497.0
#: The tolerances at which lengths are compared unscaled, and the scale beyond.
_LOW = 2.0**-200
_HIGH = 2.0**200
_UP = 2.0**400
#: The least positive float, ``math.ulp(0.0)``.
_TINIEST = 5e-324
#: :func:`goal_verdict`'s bounds of the tolerance's band, relative to the tolerance.
_SHRINK = 1.0 - _HYPOT_MARGIN
_WIDEN = 1.0 + _HYPOT_MARGIN
#: Above it, ``hypot`` is a normal float, within a few ulps (relative) of the true
#: length, and so are the band's bounds computed from a tolerance.
_FLOOR = 2.0**-960

#: :func:`goal_verdict`'s answers: not at the goal, at it, and to be decided exactly.
OUTSIDE = 0
INSIDE = 1
UNDECIDED = 2


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
    ended those runs 5e-10 to 8e-10 m away (review 38, REV38). :func:`at_goal`
    computes the same without ``math.ulp``, which numba lacks.

    Examples
    --------
    >>> resolution(4.6e6, 4.6e6), resolution(4.6e6, 0.5)
    (9.313225746154785e-10, 1.1102230246251565e-16)
    """
    return math.ulp(min(abs(x), abs(y)))


def at_goal(px: float, py: float, gx: float, gy: float, tolerance: float) -> bool:
    """Whether a robot at ``(px, py)`` has reached the goal ``(gx, gy)`` (m, finite).

    Whether the offset ``goal - robot`` (as floats) is at most ``tolerance`` (m,
    > 0) long, or at most the goal's :func:`resolution` long if that is larger.
    Exactly: ``dx² + dy² <= tolerance²`` in real arithmetic, so that the answer
    depends on no ``hypot`` implementation. ``math.hypot`` decides it where it
    is more than 2**-48 (relative) from the tolerance (:func:`goal_verdict`);
    nearer, the sign of ``dx² + dy² - tolerance²`` is found without rounding
    (Dekker's exact products, summed into a nonoverlapping expansion by
    Shewchuk's Grow-Expansion, whose largest nonzero component has the sum's
    sign). A NaN offset is not at the goal.

    Parameters
    ----------
    px, py : float
        The robot's position, m.
    gx, gy : float
        The goal's position, m.
    tolerance : float
        The goal tolerance, m, > 0.

    Returns
    -------
    bool
        Whether the robot is at the goal.

    Examples
    --------
    >>> at_goal(1.0, 2.0, 1.0, 2.05, 0.05), at_goal(1.0, 2.0, 1.0, 2.0500001, 0.05)
    (True, False)
    >>> at_goal(0.0, 0.0, 3.0, 4.0, 5.0), at_goal(0.0, 0.0, 0.5000000000000001, 0.0, 0.5)
    (True, False)

    The floats nearest 0.3 and 0.4 make an offset longer than 0.5 (by 2e-17 m),
    which ``math.hypot`` rounds to 0.5:

    >>> at_goal(0.0, 0.0, 0.3, 0.4, 0.5), math.hypot(0.3, 0.4)
    (False, 0.5)
    """
    verdict = goal_verdict(px, py, gx, gy, tolerance)
    if verdict != UNDECIDED:
        return verdict == INSIDE
    return _on_the_band(px, py, gx, gy, tolerance)


def goal_verdict(px: float, py: float, gx: float, gy: float, tolerance: float) -> int:
    """:func:`at_goal`'s answer where ``math.hypot`` decides it, else ``UNDECIDED``.

    ``INSIDE`` where the offset's ``hypot`` is below ``(1 - 2**-48) tolerance``,
    ``OUTSIDE`` where it is above ``1 + 2**-48`` times the tolerance and the
    goal's :func:`resolution` (or NaN); ``UNDECIDED`` on the band between (and
    where tolerance, resolution and ``hypot`` are all below 2**-960 m, too small
    for these bounds). A few float operations, compiled into the simulator's
    run kernels (:data:`goal_verdict_kernel`), which leave an undecided step to
    :func:`at_goal` in Python.

    Why the answers are :func:`at_goal`'s: ``hypot`` (CPython's and libm's)
    is within an ulp of the offset's true length ``r``, and the bounds allow
    four: 2**-50 relative where it is above 2**-1022 m, 2**-1072 m below. The
    bounds, computed in floats, are within 2**-53 (relative) of their real
    values and are normal floats. So ``INSIDE`` has ``r <= hypot (1 + 2**-50)
    < tolerance`` (below 2**-1022 m: ``r <= hypot + 2**-1072 < tolerance``,
    the tolerance being above 2**-960 m), and ``OUTSIDE`` has ``r >= hypot (1 -
    2**-50) > max(tolerance, 2**-52 g + 2**-960)``, which is at least the
    radius :func:`at_goal` compares with (the goal's resolution, ``math.ulp(g)``
    of its finer coordinate ``g``, is at most ``2**-52 g`` or the least float).

    Parameters
    ----------
    px, py : float
        The robot's position, m.
    gx, gy : float
        The goal's position, m.
    tolerance : float
        The goal tolerance, m, > 0.

    Returns
    -------
    int
        ``INSIDE`` (1), ``OUTSIDE`` (0) or ``UNDECIDED`` (2).

    Examples
    --------
    >>> goal_verdict(0.0, 0.0, 0.3, 0.39, 0.5), goal_verdict(0.0, 0.0, 0.3, 0.41, 0.5)
    (1, 0)

    Offsets on the tolerance's circle are left to :func:`at_goal`:

    >>> goal_verdict(0.0, 0.0, 0.3, 0.4, 0.5), at_goal(0.0, 0.0, 0.3, 0.4, 0.5)
    (2, False)
    """
    d = math.hypot(gx - px, gy - py)
    # The radius at_goal compares with is at most this. (Comparisons, not min and
    # max: each of those is a function for numba to compile, and slower in Python.)
    g = abs(gx)
    if abs(gy) < g:
        g = abs(gy)
    radius = _EPSILON * g + _FLOOR
    if radius < tolerance:
        radius = tolerance
    if not d <= radius * _WIDEN:
        return OUTSIDE  # (a NaN offset too)
    if d < tolerance * _SHRINK and tolerance > _FLOOR:
        return INSIDE
    return UNDECIDED


def _on_the_band(px: float, py: float, gx: float, gy: float, tolerance: float) -> bool:
    """:func:`at_goal` in exact arithmetic, for the offsets :func:`goal_verdict` leaves."""
    dx = gx - px
    dy = gy - py
    if math.isnan(dx) or math.isnan(dy):
        # Not left to the comparisons below: max() and min() drop a NaN second
        # argument, and a NaN dy beside a short dx was at the goal.
        return False
    t = tolerance
    g = min(abs(gx), abs(gy))
    if not t > _EPSILON * g:
        # The goal's resolution may exceed the tolerance (it is at most 2**-52 * g):
        # math.ulp(g) is 2**-52 times g's leading power of two (Rump's "unit in the
        # first place": |q - (1 - 2**-53) q| for q = (2**52 + 1) g), the least float
        # for 0 and the subnormals.
        scale = 1.0
        if g > _HIGH:  # (q would overflow beyond 2**970)
            g, scale = g / _UP, _UP
        q = _PHI * g
        t = max(t, abs(q - (1.0 - 2.0**-53) * q) * _EPSILON * scale, _TINIEST)
    a = max(abs(dx), abs(dy))
    b0 = min(abs(dx), abs(dy))
    b = b0
    # Scaled by powers of two (exactly, for every length that matters) to a
    # tolerance in [2**-200, 2**200], clear of overflow and underflow below.
    while t < _LOW:
        t, a, b = t * _UP, a * _UP, b * _UP
    while _HIGH < t < math.inf:  # (an infinite tolerance, refused by every caller: no hang)
        t, a, b = t / _UP, a / _UP, b / _UP
    if a >= t:
        return a == t and b0 == 0.0
    d = math.hypot(a, b)
    if not abs(d - t) <= _HYPOT_MARGIN * t:
        return d < t  # (NaN: False)
    if b < _TINY_SIDE * t:
        # b² < 2**-120 t², below (t - a)(t + a) >= 2**-54 t * 1.7 t (t - a is at
        # least an ulp of a): inside.
        return True
    # a² + b² - t² = b² - (t - a)(t + a): t - a is exact (Sterbenz: the offset is
    # within 2**-47 of t long, so a >= 0.7 t); t + a = q + tau exactly (Knuth's
    # two-sum), and (t - a) * tau is exact (tau is 0 or an ulp of a, or two). Written
    # out: a kernel can call no Python function.
    delta = t - a
    q = t + a
    v = q - t
    tau = (t - (q - v)) + (a - v)
    # Dekker's exact products b * b = p + pe and delta * q = r + re, from
    # Veltkamp's halves of 26 bits (no overflow or underflow here).
    c = _SPLIT * b
    bh = c - (c - b)
    bl = b - bh
    p = b * b
    pe = ((bh * bh - p) + 2.0 * bh * bl) + bl * bl
    c = _SPLIT * delta
    dh = c - (c - delta)
    dl = delta - dh
    c = _SPLIT * q
    qh = c - (c - q)
    ql = q - qh
    r = delta * q
    re = ((dh * qh - r) + dh * ql + dl * qh) + dl * ql
    # p + pe - r - re - delta * tau as a nonoverlapping expansion e1 <= ... <= e5
    # (Shewchuk's Grow-Expansion): each term is carried up the expansion by exact
    # two-sums, "s = x + y; v = s - x; err = (x - (s - v)) + (y - v)", x the carry.
    x = -re
    e2 = x + pe
    v = e2 - x
    e1 = (x - (e2 - v)) + (pe - v)
    x = -delta * tau
    s = x + e1
    v = s - x
    e1 = (x - (s - v)) + (e1 - v)
    e3 = s + e2
    v = e3 - s
    e2 = (s - (e3 - v)) + (e2 - v)
    x = p
    s = x + e1
    v = s - x
    e1 = (x - (s - v)) + (e1 - v)
    x = s + e2
    v = x - s
    e2 = (s - (x - v)) + (e2 - v)
    e4 = x + e3
    v = e4 - x
    e3 = (x - (e4 - v)) + (e3 - v)
    x = -r
    s = x + e1
    v = s - x
    e1 = (x - (s - v)) + (e1 - v)
    x = s + e2
    v = x - s
    e2 = (s - (x - v)) + (e2 - v)
    s = x + e3
    v = s - x
    e3 = (x - (s - v)) + (e3 - v)
    e5 = s + e4
    v = e5 - s
    e4 = (s - (e5 - v)) + (e4 - v)
    for s in (e5, e4, e3, e2, e1):
        if s != 0.0:
            return s < 0.0
    return True  # on the circle itself


#: :func:`goal_verdict` compiled for the simulator's run kernels (inlined by LLVM).
goal_verdict_kernel = njit_force_inline(goal_verdict)
