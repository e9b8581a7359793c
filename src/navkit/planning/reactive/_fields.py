"""Artificial potential fields: attraction, repulsion and their sums.

Every field maps world points ``(x, y)`` (m) to a scalar potential and to the
force ``-∇U``, both vectorised over ``(N, 2)`` point arrays with analytic
gradients. Fields add: ``field_a + field_b`` is a :class:`CompositeField` whose
potential and force are the sums of its parts (``sum(fields)`` works too).
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.spatial import cKDTree
from scipy.special import expit

from navkit._shared.validation import as_float_array, as_points, positive_float

__all__ = [
    "AttractiveField",
    "BlendedAttraction",
    "CompositeField",
    "ConicAttraction",
    "FieldGrid",
    "KhatibRepulsion",
    "ParaboloidAttraction",
    "PiecewiseAttraction",
    "PiecewiseRepulsion",
    "PotentialField",
    "field_grid",
]

FloatArray = NDArray[np.float64]

# Up to this many (point, obstacle) pairs are formed directly; beyond it the
# pairs within reach are found with k-d trees (a 1200 x 1200 grid against a scan).
_PAIR_BLOCK = 1 << 18
# Points per k-d tree query block when there are more pairs than that.
_TREE_BLOCK = 1 << 22


class PotentialField(ABC):
    """Base class of navkit's potential fields (immutable).

    Subclasses implement ``_potential`` and ``_force`` on a validated ``(N, 2)``
    float64 array; the public :meth:`potential` and :meth:`force` validate once.
    Inputs are copied: changing an array after building a field does not change it.

    Examples
    --------
    >>> fields = [ConicAttraction((1.0, 0.0)), KhatibRepulsion([[0.5, 0.5]], d0=0.5)]
    >>> total = sum(fields)                  # the obstacle is 0.71 m away, beyond d0
    >>> total.force([0.0, 0.0]), total.potential([0.0, 0.0])
    (array([[1., 0.]]), array([1.]))
    """

    __slots__ = ()

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(f"{type(self).__name__} is immutable")

    def _set(self, name: str, value: Any) -> None:
        object.__setattr__(self, name, value)

    def potential(self, points: ArrayLike) -> FloatArray:
        """Potential energy at world points.

        Parameters
        ----------
        points : array_like, shape (N, 2) or (2,)
            ``(x, y)`` positions in metres; a single point gives ``N = 1``.

        Returns
        -------
        ndarray, shape (N,)
            The potential ``U`` at each point (``+inf`` on a Khatib obstacle).
        """
        return self._potential(as_points(points, "points"))

    def force(self, points: ArrayLike) -> FloatArray:
        """Force ``-∇U`` at world points.

        Parameters
        ----------
        points : array_like, shape (N, 2) or (2,)
            ``(x, y)`` positions in metres; a single point gives ``N = 1``.

        Returns
        -------
        ndarray, shape (N, 2)
            The force ``(Fx, Fy)`` at each point, in the world frame.
        """
        return self._force(as_points(points, "points"))

    @abstractmethod
    def _potential(self, pts: FloatArray) -> FloatArray: ...

    @abstractmethod
    def _force(self, pts: FloatArray) -> FloatArray: ...

    def _parts(self) -> tuple[PotentialField, ...]:
        return (self,)

    def __add__(self, other: PotentialField) -> CompositeField:
        if not isinstance(other, PotentialField):
            return NotImplemented
        return CompositeField(*self._parts(), *other._parts())

    def __radd__(self, other: object) -> PotentialField:
        # Lets ``sum(fields)`` start from its integer 0.
        if isinstance(other, int) and other == 0:
            return self
        return NotImplemented

    def __repr__(self) -> str:
        args = ", ".join(f"{name}={_short(getattr(self, name))}" for name in self._repr_names())
        return f"{type(self).__name__}({args})"

    def _repr_names(self) -> tuple[str, ...]:
        names: list[str] = []
        for klass in reversed(type(self).__mro__):
            names.extend(n for n in getattr(klass, "__slots__", ()) if not n.startswith("_"))
        return tuple(names)


def _short(value: Any) -> str:
    if isinstance(value, np.ndarray):
        if value.ndim == 1:
            return "(" + ", ".join(repr(float(v)) for v in value) + ")"
        return f"<array shape={value.shape}>"
    return repr(value)


def _frozen(arr: FloatArray) -> FloatArray:
    out = np.array(arr, dtype=np.float64, copy=True)
    out.setflags(write=False)
    return out


def _goal(goal: ArrayLike) -> FloatArray:
    return _frozen(as_float_array(goal, "goal", shape=(2,)))


def _obstacles(obstacles: ArrayLike) -> FloatArray:
    return _frozen(as_points(obstacles, "obstacles"))


def _offsets(pts: FloatArray, centre: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Offsets ``pts - centre`` and their norms."""
    diff = pts - centre
    return diff, np.hypot(diff[:, 0], diff[:, 1])


def _unit(diff: FloatArray, d: FloatArray) -> FloatArray:
    """``diff / d`` row-wise, with the zero vector where ``d == 0``."""
    safe = np.where(d > 0.0, d, 1.0)
    return np.where((d > 0.0)[:, None], diff / safe[:, None], 0.0)


class AttractiveField(PotentialField):
    """Base of the attractive fields: a field pulling toward one ``goal`` point."""

    __slots__ = ("goal",)
    goal: FloatArray

    def with_goal(self, goal: ArrayLike) -> AttractiveField:
        """Return the same field (all parameters kept) centred on a new goal ``(x, y)``.

        Examples
        --------
        >>> ConicAttraction((0.0, 0.0), m=2.0).with_goal((1.0, 1.0)).goal
        array([1., 1.])
        """
        out = object.__new__(type(self))
        for name in self._repr_names():
            out._set(name, getattr(self, name))
        out._set("goal", _goal(goal))
        return out


class ParaboloidAttraction(AttractiveField):
    """Elliptic paraboloid attraction ``U = K_att·c·((x - xd)²/a² + (y - yd)²/b²)``.

    The near-goal limit (σ → 0) of :class:`BlendedAttraction`.

    Parameters
    ----------
    goal : array_like, shape (2,)
        Goal ``(xd, yd)`` in metres.
    k_att : float, default 1.0
        Attraction gain, > 0.
    c : float, default 1.0
        Curvature, > 0.
    a, b : float, default 1.0
        Ellipse semi-axes along x and y (m), > 0.

    Examples
    --------
    >>> field = ParaboloidAttraction((1.0, 0.0), k_att=2.0, a=1.0, b=2.0)
    >>> field.potential([[0.0, 2.0]])
    array([4.])
    >>> field.force([[0.0, 2.0]])
    array([[ 4., -2.]])
    """

    __slots__ = ("a", "b", "c", "k_att")
    k_att: float
    c: float
    a: float
    b: float

    def __init__(
        self, goal: ArrayLike, *, k_att: float = 1.0, c: float = 1.0, a: float = 1.0, b: float = 1.0
    ) -> None:
        self._set("goal", _goal(goal))
        self._set("k_att", positive_float(k_att, "k_att"))
        self._set("c", positive_float(c, "c"))
        self._set("a", positive_float(a, "a"))
        self._set("b", positive_float(b, "b"))

    def _scales(self) -> tuple[float, float]:
        kc = self.k_att * self.c
        return kc / (self.a * self.a), kc / (self.b * self.b)

    def _potential(self, pts: FloatArray) -> FloatArray:
        sx, sy = self._scales()
        diff = pts - self.goal
        out: FloatArray = sx * diff[:, 0] ** 2 + sy * diff[:, 1] ** 2
        return out

    def _force(self, pts: FloatArray) -> FloatArray:
        sx, sy = self._scales()
        diff = pts - self.goal
        return np.stack((0.0 - 2.0 * sx * diff[:, 0], 0.0 - 2.0 * sy * diff[:, 1]), axis=1)


class ConicAttraction(AttractiveField):
    """Linear cone attraction ``U = m·(d - rad_thr)·U_trans``, ``d = ‖q - q_d‖``.

    The far-from-goal limit (σ → 1) of :class:`BlendedAttraction`: the force has
    the constant magnitude ``m·U_trans`` everywhere except at the goal itself,
    where the cone's tip has no gradient and the force is defined as zero.

    Parameters
    ----------
    goal : array_like, shape (2,)
        Goal ``(xd, yd)`` in metres.
    m : float, default 1.0
        Gradient (speed), > 0.
    u_trans : float, default 1.0
        Translation constant, > 0.
    rad_thr : float, default 0.0
        Offset of the cone (m), >= 0; shifts the potential only.

    Examples
    --------
    >>> ConicAttraction((0.0, 0.0), m=0.5).force([[3.0, 4.0]])
    array([[-0.3, -0.4]])
    """

    __slots__ = ("m", "rad_thr", "u_trans")
    m: float
    u_trans: float
    rad_thr: float

    def __init__(
        self, goal: ArrayLike, *, m: float = 1.0, u_trans: float = 1.0, rad_thr: float = 0.0
    ) -> None:
        self._set("goal", _goal(goal))
        self._set("m", positive_float(m, "m"))
        self._set("u_trans", positive_float(u_trans, "u_trans"))
        self._set("rad_thr", positive_float(rad_thr, "rad_thr", allow_zero=True))

    def _potential(self, pts: FloatArray) -> FloatArray:
        _, d = _offsets(pts, self.goal)
        out: FloatArray = self.m * self.u_trans * (d - self.rad_thr)
        return out

    def _force(self, pts: FloatArray) -> FloatArray:
        diff, d = _offsets(pts, self.goal)
        # ``0.0 - x`` rather than ``-x`` so zero components print as 0, not -0.
        out: FloatArray = 0.0 - self.m * self.u_trans * _unit(diff, d)
        return out


class BlendedAttraction(AttractiveField):
    """Paraboloid near the goal blended into a cone far away by a sigmoid.

    With ``d = ‖q - q_d‖`` and ``σ(d) = ½[tanh((d - rad_thr)/ω) + 1]``::

        U_par  = K_att·c·((x - xd)²/a² + (y - yd)²/b²)
        U_cone = m·(d - rad_thr)·U_trans
        U      = [1 - σ(d)]·U_par + σ(d)·U_cone

    and the force is the full gradient, blending terms included::

        -∇U = -[1 - σ]·∇U_par - σ·m·U_trans·∇d - σ'(d)·(U_cone - U_par)·∇d,
        σ'(d) = (2/ω)·σ·(1 - σ),  ∇d = (q - q_d)/d.

    σ and 1 - σ are evaluated as ``expit(±2(d - rad_thr)/ω)`` (the same function
    as the tanh form) so neither loses precision where it is tiny. At the goal
    itself ``∇d`` is undefined (the cone's tip); its terms are taken as zero there.

    Parameters
    ----------
    goal : array_like, shape (2,)
        Goal ``(xd, yd)`` in metres.
    k_att, c : float, default 1.0
        Paraboloid gain and curvature, > 0.
    a, b : float, default 1.0
        Ellipse semi-axes (m), > 0.
    rad_thr : float, default 0.5
        Distance (m) at which σ = ½, >= 0.
    width : float, default 0.15
        Blending width ω (m), > 0: σ goes from 0.12 to 0.88 over ``rad_thr ± ω``.
    m : float, default 1.0
        Cone gradient (speed), > 0.
    u_trans : float, default 1.0
        Translation constant, > 0.

    Notes
    -----
    The blend is not automatically free of spurious minima. At ``d = rad_thr``
    the cone term is 0 while the paraboloid is ``K_att·c·rad_thr²`` (circular
    case), so the ``σ'(U_cone - U_par)`` term pulls the robot outward with up to
    ``K_att·c·rad_thr²/(2ω)``; when that exceeds the inward
    ``K_att·c·rad_thr + m·U_trans/2`` the field has a ring of local minima just
    outside ``rad_thr`` (narrow widths, large ``rad_thr``). Inside, σ(0) > 0 and the
    cone's negative offset displace the minimum from the goal, to first order by
    ``σ(0)·m·U_trans·(2·rad_thr/ω - 1)/(2·K_att·c)``. The defaults
    (``K_att = c = a = b = m = U_trans = 1``, ``rad_thr = 0.5``, ``ω = 0.15``)
    pull toward the goal everywhere beyond 4 mm, where the minimum lies (3.75 mm);
    with ``rad_thr = 0.5`` a width of 0.1 has the ring at 0.55 m and widths of 0.3
    to 0.5 a minimum 4.6 cm from the goal. Check a chosen parameter set with
    :func:`field_grid` or a radial profile (``tests/control/test_blending_widths.py``
    compares widths in closed loop).

    Examples
    --------
    >>> field = BlendedAttraction((0.0, 0.0), rad_thr=1.0, width=0.1)
    >>> far = field.force([[30.0, 40.0]])          # the cone: magnitude m·U_trans
    >>> bool(np.allclose(far, [[-0.6, -0.8]]))
    True
    >>> near = field.force([[0.1, 0.0]])           # the paraboloid: -2·K_att·c·x/a²
    >>> bool(np.allclose(near, [[-0.2, 0.0]]))
    True
    """

    __slots__ = ("a", "b", "c", "k_att", "m", "rad_thr", "u_trans", "width")
    k_att: float
    c: float
    a: float
    b: float
    rad_thr: float
    width: float
    m: float
    u_trans: float

    def __init__(
        self,
        goal: ArrayLike,
        *,
        k_att: float = 1.0,
        c: float = 1.0,
        a: float = 1.0,
        b: float = 1.0,
        rad_thr: float = 0.5,
        width: float = 0.15,
        m: float = 1.0,
        u_trans: float = 1.0,
    ) -> None:
        self._set("goal", _goal(goal))
        self._set("k_att", positive_float(k_att, "k_att"))
        self._set("c", positive_float(c, "c"))
        self._set("a", positive_float(a, "a"))
        self._set("b", positive_float(b, "b"))
        self._set("rad_thr", positive_float(rad_thr, "rad_thr", allow_zero=True))
        self._set("width", positive_float(width, "width"))
        self._set("m", positive_float(m, "m"))
        self._set("u_trans", positive_float(u_trans, "u_trans"))

    def sigma(self, d: ArrayLike) -> FloatArray:
        """Blending function σ(d) = ½[tanh((d - rad_thr)/ω) + 1] for distances ``d`` (m).

        Examples
        --------
        >>> BlendedAttraction((0.0, 0.0), rad_thr=1.0).sigma([1.0])
        array([0.5])
        """
        dist = as_float_array(d, "d")
        out: FloatArray = expit(2.0 * (dist - self.rad_thr) / self.width)
        return out

    def _terms(
        self, pts: FloatArray
    ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
        diff, d = _offsets(pts, self.goal)
        z = 2.0 * (d - self.rad_thr) / self.width
        sig = expit(z)
        one_minus = expit(-z)
        kc = self.k_att * self.c
        u_par = kc * (diff[:, 0] ** 2 / self.a**2 + diff[:, 1] ** 2 / self.b**2)
        u_cone = self.m * self.u_trans * (d - self.rad_thr)
        return diff, d, sig, one_minus, u_par, u_cone

    def _potential(self, pts: FloatArray) -> FloatArray:
        _, _, sig, one_minus, u_par, u_cone = self._terms(pts)
        out: FloatArray = one_minus * u_par + sig * u_cone
        return out

    def _force(self, pts: FloatArray) -> FloatArray:
        diff, d, sig, one_minus, u_par, u_cone = self._terms(pts)
        kc2 = 2.0 * self.k_att * self.c
        grad_par = np.stack((kc2 * diff[:, 0] / self.a**2, kc2 * diff[:, 1] / self.b**2), axis=1)
        dsigma = (2.0 / self.width) * sig * one_minus
        radial = sig * self.m * self.u_trans + dsigma * (u_cone - u_par)
        grad = one_minus[:, None] * grad_par + radial[:, None] * _unit(diff, d)
        out: FloatArray = 0.0 - grad
        return out


class PiecewiseAttraction(AttractiveField):
    """Piecewise-linear attraction of the omnidirectional LiDAR robot (Goodrich's form).

    With ``d`` the distance to the goal, the force points at the goal with
    magnitude ``0`` for ``d < r``, ``α(d - r)`` for ``r <= d <= s + r`` and
    ``α·s`` beyond. The paper writes ``α`` for the last piece, which is
    dimensionally inconsistent and makes the force jump at ``d = s + r``; ``α·s``
    (Goodrich's potential-field tutorial) is the continuous form used here. The
    potential is its integral, ``0``, ``½α(d - r)²`` and ``½α·s² + α·s(d - s - r)``.

    Parameters
    ----------
    goal : array_like, shape (2,)
        Goal ``(xd, yd)`` in metres.
    alpha : float, default 1.0
        Gain (1/s for a velocity field), > 0.
    r : float, default 0.0
        Goal radius (m) inside which there is no force, >= 0.
    s : float, default 1.0
        Width of the linear zone (m), > 0.

    Examples
    --------
    >>> field = PiecewiseAttraction((0.0, 0.0), alpha=2.0, r=0.5, s=1.0)
    >>> field.force([[0.25, 0.0], [1.0, 0.0], [10.0, 0.0]])
    array([[ 0.,  0.],
           [-1.,  0.],
           [-2.,  0.]])
    """

    __slots__ = ("alpha", "r", "s")
    alpha: float
    r: float
    s: float

    def __init__(
        self, goal: ArrayLike, *, alpha: float = 1.0, r: float = 0.0, s: float = 1.0
    ) -> None:
        self._set("goal", _goal(goal))
        self._set("alpha", positive_float(alpha, "alpha"))
        self._set("r", positive_float(r, "r", allow_zero=True))
        self._set("s", positive_float(s, "s"))

    def _potential(self, pts: FloatArray) -> FloatArray:
        _, d = _offsets(pts, self.goal)
        a, r, s = self.alpha, self.r, self.s
        lin = np.clip(d - r, 0.0, s)
        out: FloatArray = 0.5 * a * lin**2 + a * s * np.maximum(d - s - r, 0.0)
        return out

    def _force(self, pts: FloatArray) -> FloatArray:
        diff, d = _offsets(pts, self.goal)
        mag = self.alpha * np.clip(d - self.r, 0.0, self.s)
        out: FloatArray = 0.0 - mag[:, None] * _unit(diff, d)
        return out


class _PointRepulsion(PotentialField):
    """Sum over obstacle points of a radial repulsion with a finite reach.

    Only (point, obstacle) pairs within the reach contribute, so they are gathered
    first and the radial law is evaluated on them alone; pairs are formed in
    blocks of bounded size so that large grids against many obstacles fit in memory.
    """

    __slots__ = ("_kdtree", "obstacles")
    obstacles: FloatArray

    @abstractmethod
    def _reach(self) -> float:
        """Distance beyond which an obstacle contributes exactly nothing."""

    @abstractmethod
    def _radial(self, d: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Potential and outward force magnitude for distances ``0 <= d <= reach``."""

    def _near_pairs(
        self, pts: FloatArray
    ) -> Iterator[tuple[slice, NDArray[np.intp], FloatArray, FloatArray, FloatArray]]:
        """Per block: point indices (within the block), dx, dy and d of pairs in reach.

        Small problems form every pair; large ones (grids for plots) find the pairs
        within reach with k-d trees, so the cost follows the pairs that matter.
        """
        m = self.obstacles.shape[0]
        n = pts.shape[0]
        reach = self._reach()
        dense = n * m <= _PAIR_BLOCK
        step = n if dense else max(1, _TREE_BLOCK // m)
        for start in range(0, n, step):
            block = slice(start, min(n, start + step))
            if dense:
                dx = pts[block, 0, None] - self.obstacles[None, :, 0]
                dy = pts[block, 1, None] - self.obstacles[None, :, 1]
                rows, cols = np.nonzero(np.hypot(dx, dy) <= reach)
                dx = dx[rows, cols]
                dy = dy[rows, cols]
            else:
                found = cKDTree(pts[block]).sparse_distance_matrix(
                    self._tree(), reach, output_type="ndarray"
                )
                rows, cols = found["i"], found["j"]
                dx = pts[block][rows, 0] - self.obstacles[cols, 0]
                dy = pts[block][rows, 1] - self.obstacles[cols, 1]
            # Distances are recomputed the same way on both paths, so the pair set
            # and the values agree to the last bit at every point except exactly at
            # the reach, where every radial law here is zero anyway.
            d = np.hypot(dx, dy)
            keep = d <= reach
            yield block, rows[keep].astype(np.intp), dx[keep], dy[keep], d[keep]

    def _tree(self) -> Any:
        tree = getattr(self, "_kdtree", None)
        if tree is None:
            tree = cKDTree(self.obstacles)
            self._set("_kdtree", tree)
        return tree

    def _potential(self, pts: FloatArray) -> FloatArray:
        out = np.zeros(pts.shape[0], dtype=np.float64)
        if self.obstacles.shape[0] == 0:
            return out
        for block, idx, _, _, d in self._near_pairs(pts):
            u, _ = self._radial(d)
            out[block] = np.bincount(idx, weights=u, minlength=block.stop - block.start)
        return out

    def _force(self, pts: FloatArray) -> FloatArray:
        out = np.zeros((pts.shape[0], 2), dtype=np.float64)
        if self.obstacles.shape[0] == 0:
            return out
        for block, idx, dx, dy, d in self._near_pairs(pts):
            _, mag = self._radial(d)
            # Direction (q - q_c)/d; a point on an obstacle has none and gets 0.
            with np.errstate(over="ignore"):
                coef = np.where(d > 0.0, mag / np.where(d > 0.0, d, 1.0), 0.0)
            # A magnitude that overflowed to inf (d below ~1e-103) must not turn the
            # zero component of its direction into NaN.
            with np.errstate(invalid="ignore"):
                fx = np.where(dx != 0.0, coef * dx, 0.0)
                fy = np.where(dy != 0.0, coef * dy, 0.0)
            n = block.stop - block.start
            out[block, 0] = np.bincount(idx, weights=fx, minlength=n)
            out[block, 1] = np.bincount(idx, weights=fy, minlength=n)
        return out


class KhatibRepulsion(_PointRepulsion):
    """Khatib's FIRAS repulsion summed over obstacle points.

    For each obstacle ``q_c`` at distance ``d = ‖q - q_c‖``::

        U = ½·k_rep·(1/d - 1/d0)²                       for d <= d0, else 0
        F = k_rep·(1/d - 1/d0)·(1/d²)·(q - q_c)/d       for d <= d0, else 0

    Exactly zero beyond ``d0``, continuous at ``d0`` and unbounded as ``d → 0``.
    At a point coinciding with an obstacle the potential is ``+inf`` and that
    obstacle's force, whose direction is undefined, is zero.

    Parameters
    ----------
    obstacles : array_like, shape (M, 2)
        Obstacle points ``(x, y)`` in metres; ``M = 0`` is valid (zero field).
    k_rep : float, default 1.0
        Repulsion gain, > 0.
    d0 : float, default 1.0
        Influence distance (m), > 0.

    Examples
    --------
    >>> field = KhatibRepulsion([[0.0, 0.0]], k_rep=1.0, d0=1.0)
    >>> field.force([[0.5, 0.0], [2.0, 0.0]])      # (1/0.5 - 1)/0.5² = 4
    array([[4., 0.],
           [0., 0.]])
    >>> field.potential([[0.5, 0.0]])
    array([0.5])
    """

    __slots__ = ("d0", "k_rep")
    k_rep: float
    d0: float

    def __init__(self, obstacles: ArrayLike, *, k_rep: float = 1.0, d0: float = 1.0) -> None:
        self._set("obstacles", _obstacles(obstacles))
        self._set("k_rep", positive_float(k_rep, "k_rep"))
        self._set("d0", positive_float(d0, "d0"))

    def _reach(self) -> float:
        return self.d0

    def _radial(self, d: FloatArray) -> tuple[FloatArray, FloatArray]:
        # Unbounded near an obstacle: overflow to +inf is the right answer there.
        with np.errstate(divide="ignore", over="ignore"):
            excess = 1.0 / d - 1.0 / self.d0
            mag = self.k_rep * excess / (d * d)
            return 0.5 * self.k_rep * excess * excess, mag


class PiecewiseRepulsion(_PointRepulsion):
    """Piecewise-linear repulsion of the omnidirectional LiDAR robot, per obstacle point.

    With ``d`` the distance to an obstacle and ``û`` the unit vector toward it,
    the force is ``-δ·û`` for ``d < r``, ``-β(s + r - d)·û`` for
    ``r <= d <= s + r`` and zero beyond. The potential is its integral,
    ``½β·s² + δ(r - d)``, ``½β(s + r - d)²`` and ``0``. The force jumps at
    ``d = r`` unless ``δ = β·s``; on the obstacle itself it is zero.

    Parameters
    ----------
    obstacles : array_like, shape (M, 2)
        Obstacle points ``(x, y)`` in metres; ``M = 0`` is valid (zero field).
    delta : float, default 1.0
        Force magnitude inside radius ``r``, > 0.
    beta : float, default 1.0
        Gain of the linear zone, > 0.
    r : float, default 0.0
        Obstacle (or safety) radius (m), >= 0.
    s : float, default 1.0
        Width of the linear zone (m), > 0.

    Examples
    --------
    >>> field = PiecewiseRepulsion([[0.0, 0.0]], delta=5.0, beta=2.0, r=0.5, s=1.0)
    >>> field.force([[0.2, 0.0], [1.0, 0.0], [2.0, 0.0]])
    array([[5., 0.],
           [1., 0.],
           [0., 0.]])
    """

    __slots__ = ("beta", "delta", "r", "s")
    delta: float
    beta: float
    r: float
    s: float

    def __init__(
        self,
        obstacles: ArrayLike,
        *,
        delta: float = 1.0,
        beta: float = 1.0,
        r: float = 0.0,
        s: float = 1.0,
    ) -> None:
        self._set("obstacles", _obstacles(obstacles))
        self._set("delta", positive_float(delta, "delta"))
        self._set("beta", positive_float(beta, "beta"))
        self._set("r", positive_float(r, "r", allow_zero=True))
        self._set("s", positive_float(s, "s"))

    def _reach(self) -> float:
        return self.s + self.r

    def _radial(self, d: FloatArray) -> tuple[FloatArray, FloatArray]:
        reach = self.s + self.r
        lin = np.clip(reach - d, 0.0, self.s)
        core = np.maximum(self.r - d, 0.0)
        u = 0.5 * self.beta * lin * lin + self.delta * core
        mag = np.where(d < self.r, self.delta, self.beta * lin)
        return u, mag


class CompositeField(PotentialField):
    """Sum of fields: potential and force add up.

    Usually built with ``+``; nested sums are flattened.

    Parameters
    ----------
    *fields : PotentialField
        The parts; none is allowed (the zero field).

    Examples
    --------
    >>> total = ConicAttraction((5.0, 0.0)) + KhatibRepulsion([[1.0, 0.0]], d0=2.0)
    >>> len(total.fields)
    2
    >>> total.force([[0.0, 0.0]])        # pulled +x by 1, pushed -x by (1 - 1/2)/1 = 0.5
    array([[0.5, 0. ]])
    """

    __slots__ = ("fields",)
    fields: tuple[PotentialField, ...]

    def __init__(self, *fields: PotentialField) -> None:
        parts: list[PotentialField] = []
        for i, field in enumerate(fields):
            if not isinstance(field, PotentialField):
                raise TypeError(f"fields[{i}] must be a PotentialField, got {type(field).__name__}")
            parts.extend(field._parts())
        self._set("fields", tuple(parts))

    def _parts(self) -> tuple[PotentialField, ...]:
        return self.fields

    def _potential(self, pts: FloatArray) -> FloatArray:
        out = np.zeros(pts.shape[0], dtype=np.float64)
        for field in self.fields:
            out += field._potential(pts)
        return out

    def _force(self, pts: FloatArray) -> FloatArray:
        out = np.zeros((pts.shape[0], 2), dtype=np.float64)
        for field in self.fields:
            out += field._force(pts)
        return out


@dataclass(frozen=True, eq=False)
class FieldGrid:
    """A field sampled on a regular grid of cell centres.

    ``potential[row, col]`` and ``force[row, col]`` are the values at the world
    point ``(x[col], y[row])``; rows run along y, columns along x.

    Attributes
    ----------
    x : ndarray, shape (W,)
        Cell-centre x coordinates (m), increasing.
    y : ndarray, shape (H,)
        Cell-centre y coordinates (m), increasing.
    potential : ndarray, shape (H, W)
        Potential at each cell centre.
    force : ndarray, shape (H, W, 2)
        Force ``(Fx, Fy)`` at each cell centre.
    """

    x: FloatArray
    y: FloatArray
    potential: FloatArray
    force: FloatArray


def _limits(value: ArrayLike, name: str) -> tuple[float, float]:
    arr = as_float_array(value, name, shape=(2,))
    lo, hi = float(arr[0]), float(arr[1])
    if not hi > lo:
        raise ValueError(f"{name} must be (min, max) with max > min, got {(lo, hi)}")
    return lo, hi


def _centres(lo: float, hi: float, resolution: float) -> FloatArray:
    # The tolerance keeps an exact multiple (12 m at 0.01 m) from gaining a cell to rounding.
    n = max(1, math.ceil((hi - lo) / resolution - 1e-9))
    out: FloatArray = lo + (np.arange(n, dtype=np.float64) + 0.5) * resolution
    return out


def field_grid(
    field: PotentialField,
    xlim: ArrayLike,
    ylim: ArrayLike,
    resolution: float,
) -> FieldGrid:
    """Evaluate a field's potential and force on a grid (e.g. for plots).

    The window ``[xlim[0], xlim[1]] × [ylim[0], ylim[1]]`` is divided into square
    cells of side ``resolution``; values are taken at cell centres, so
    ``xlim=(0, 12), resolution=0.01`` gives 1200 columns.

    Parameters
    ----------
    field : PotentialField
        Any navkit field, including composites.
    xlim, ylim : array_like, shape (2,)
        ``(min, max)`` extents in metres, ``max > min``.
    resolution : float
        Cell side in metres, > 0.

    Returns
    -------
    FieldGrid
        Coordinates, ``potential`` (H, W) and ``force`` (H, W, 2) indexed ``[row, col]``.

    Examples
    --------
    >>> grid = field_grid(ConicAttraction((0.0, 0.0)), (-1.0, 1.0), (0.0, 1.0), 0.5)
    >>> grid.potential.shape, grid.force.shape
    ((2, 4), (2, 4, 2))
    >>> grid.x
    array([-0.75, -0.25,  0.25,  0.75])
    """
    if not isinstance(field, PotentialField):
        raise TypeError(f"field must be a PotentialField, got {type(field).__name__}")
    res = positive_float(resolution, "resolution")
    x0, x1 = _limits(xlim, "xlim")
    y0, y1 = _limits(ylim, "ylim")
    xs = _centres(x0, x1, res)
    ys = _centres(y0, y1, res)
    gx, gy = np.meshgrid(xs, ys)
    pts = np.stack((gx.ravel(), gy.ravel()), axis=1)
    shape = (ys.size, xs.size)
    return FieldGrid(
        x=xs,
        y=ys,
        potential=field._potential(pts).reshape(shape),
        force=field._force(pts).reshape((*shape, 2)),
    )

