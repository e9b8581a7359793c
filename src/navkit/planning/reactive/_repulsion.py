"""Repulsive potential fields: radial pushes away from obstacle points ``obstacles_xy``.

Khatib's FIRAS repulsion and the omnidirectional LiDAR robot's piecewise-linear
repulsion, each summed over a set of obstacle points. Parameter names follow
navkit's vocabulary; each class states the paper's symbol of every parameter
(Khatib's ``d0`` is ``influence_radius``; the piecewise ``r`` is
``obstacle_radius`` and ``s`` is ``spread``).
"""

from __future__ import annotations

import itertools
from abc import abstractmethod
from collections.abc import Iterator
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.frozen import frozen_setattr
from navkit._shared.types import FloatArray
from navkit.planning.reactive._limits import MIN_DISTANCE, gain, length
from navkit.planning.reactive._potential_field import (
    PotentialField,
    _direction,
    _frozen,
    _obstacles,
    _restore,
)

__all__ = ["KhatibRepulsion", "PiecewiseRepulsion"]

# Up to this many (point, obstacle) pairs are formed directly; beyond it the
# pairs within reach are found with k-d trees (a 1200 x 1200 grid against a scan).
_PAIR_BLOCK = 1 << 18
# Points per k-d tree query block when there are more pairs than that.
_TREE_BLOCK = 1 << 22
# Below this many points per block (over 16384 obstacles), blocks are sized by the
# pairs actually in reach instead. Counting them costs a pass over the points, and
# bigger blocks leave the CPU cache: only worth it where blocks would be tiny.
_TREE_POINTS_MIN = 1 << 8
# Pairs in reach per block when they are counted. A pair costs about 140 bytes
# while its block is evaluated (its indices, offsets, distance and the radial
# law's temporaries): 1M pairs keep that near 150 MB, where 4M pairs took
# 615 MB at 10**6 obstacles, and run as fast (review 28: 10**6 obstacles
# against 10**5 points, 5.0 s either way; blocks of 0.5M pairs took 8.6 s,
# walking the tree more). _TREE_BLOCK stays: smaller blocks there cost time.
_REACH_BLOCK = 1 << 20


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False, repr=False)
class _PointRepulsion(PotentialField):
    """Sum over obstacle points of a radial repulsion with a finite reach.

    Only (point, obstacle) pairs within the reach contribute, so they are gathered
    first and the radial law is evaluated on them alone; pairs are formed in
    blocks of bounded size so that large grids against many obstacles fit in memory.
    The k-d tree of the obstacles is built on first need and cached in
    ``_kdtree`` (not an init argument, not in the repr).
    """

    obstacles_xy: FloatArray
    _kdtree: Any = field(default=None, init=False, repr=False)

    __setstate__ = _restore

    def __post_init__(self) -> None:
        object.__setattr__(self, "obstacles_xy", _obstacles(self.obstacles_xy))

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
        obstacles = self.obstacles_xy
        m = obstacles.shape[0]
        n = pts.shape[0]
        reach = self._reach()
        dense = n * m <= _PAIR_BLOCK
        step = n if dense else max(1, _TREE_BLOCK // m)
        if step >= _TREE_POINTS_MIN or step >= n:
            edges = [*range(0, n, step), n]
        else:
            # Many obstacles would make blocks of a few points, and each small block
            # of scattered points walks most of the obstacles' tree: a cost growing
            # with m². Blocks then hold about _REACH_BLOCK pairs in reach instead,
            # counted first without forming them.
            total = np.cumsum(self._tree().query_ball_point(pts, reach, return_length=True))
            bounds = np.arange(_REACH_BLOCK, total[-1], _REACH_BLOCK)
            cuts = np.searchsorted(total, bounds, "right")
            edges = np.unique(np.concatenate(([0], cuts, [n]))).tolist()
        for start, stop in itertools.pairwise(edges):
            block = slice(start, stop)
            if dense:
                dx = pts[block, 0, None] - obstacles[None, :, 0]
                dy = pts[block, 1, None] - obstacles[None, :, 1]
                rows, cols = np.nonzero(np.hypot(dx, dy) <= reach)
                dx = dx[rows, cols]
                dy = dy[rows, cols]
            else:
                from scipy.spatial import cKDTree

                found = cKDTree(pts[block]).sparse_distance_matrix(
                    self._tree(), reach, output_type="ndarray"
                )
                rows, cols = found["i"], found["j"]
                dx = pts[block][rows, 0] - obstacles[cols, 0]
                dy = pts[block][rows, 1] - obstacles[cols, 1]
                del found  # rows and cols, views of it, go below
            # Distances are recomputed the same way on both paths, so the pair set
            # and the values agree to the last bit at every point except exactly at
            # the reach, where every radial law here is zero anyway.
            d = np.hypot(dx, dy)
            keep = d <= reach
            pairs = rows[keep].astype(np.intp, copy=False), dx[keep], dy[keep], d[keep]
            # Dropped before the caller evaluates the block: a suspended generator
            # keeps its locals, a third of the block's memory.
            del rows, cols, dx, dy, d, keep
            yield block, *pairs

    def _tree(self) -> Any:
        tree = self._kdtree
        if tree is None:
            from scipy.spatial import cKDTree

            tree = cKDTree(self.obstacles_xy)
            object.__setattr__(self, "_kdtree", tree)
        return tree

    def _potential(self, pts: FloatArray) -> FloatArray:
        out = np.zeros(pts.shape[0], dtype=np.float64)
        if self.obstacles_xy.shape[0] == 0 or pts.shape[0] == 0:
            return out
        for block, idx, _, _, d in self._near_pairs(pts):
            u, _ = self._radial(d)
            out[block] = np.bincount(idx, weights=u, minlength=block.stop - block.start)
        return out

    def _force(self, pts: FloatArray) -> FloatArray:
        out = np.zeros((pts.shape[0], 2), dtype=np.float64)
        if self.obstacles_xy.shape[0] == 0 or pts.shape[0] == 0:
            return out
        for block, idx, dx, dy, d in self._near_pairs(pts):
            _, mag = self._radial(d)
            # Direction (q - q_c)/d, a unit vector even for subnormal offsets; a
            # point on an obstacle has none and gets 0. The radial laws are
            # finite (Khatib saturates below MIN_DISTANCE), so the sum has no NaN.
            ux, uy = _direction(dx, dy, d)
            fx = mag * ux
            fy = mag * uy
            n = block.stop - block.start
            out[block, 0] = np.bincount(idx, weights=fx, minlength=n)
            out[block, 1] = np.bincount(idx, weights=fy, minlength=n)
        return out


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False, repr=False, kw_only=True)
class KhatibRepulsion(_PointRepulsion):
    """Khatib's FIRAS repulsion summed over obstacle points.

    In Khatib's symbols, for each obstacle ``q_c`` at distance ``d = ‖q - q_c‖``::

        U = ½·k_rep·(1/d - 1/d0)²                       for d <= d0, else 0
        F = k_rep·(1/d - 1/d0)·(1/d²)·(q - q_c)/d       for d <= d0, else 0

    Exactly zero beyond ``d0``, continuous at ``d0`` and growing without bound
    as ``d → 0`` — down to ``d = 1e-9`` m: an obstacle nearer than that (a
    nanometre, far below any sensor's resolution) acts as if it were 1e-9 m
    away, so its push saturates at a finite ``k_rep·(1e9 - 1/d0)·1e18`` and
    opposite pushes cancel instead of giving ``inf - inf = NaN``. At a point
    coinciding with an obstacle (``d = 0``) the potential is ``+inf`` and that
    obstacle's force, whose direction is undefined, is zero. The force is
    always finite. Khatib's ``d0`` (the limit distance of the potential field
    influence) is ``influence_radius``.

    Parameters
    ----------
    obstacles_xy : array_like, shape (M, 2)
        Obstacle points ``q_c = (x, y)`` in metres, ``|x|, |y| <= 1e9``;
        ``M = 0`` is valid (zero field). Stored as a read-only copy.
    k_rep : float, default 1.0
        Repulsion gain, in ``[1e-12, 1e12]``.
    influence_radius : float, default 1.0
        Khatib's ``d0`` (m), in ``[1e-6, 1e6]``: obstacles farther than this do
        not push.

    Raises
    ------
    ValueError
        A parameter out of its range; obstacles of a bad shape, not finite or
        beyond ±1e9 m.
    TypeError
        A parameter that is not a real number (or is a bool); non-numeric
        obstacles.

    Examples
    --------
    >>> field = KhatibRepulsion([[0.0, 0.0]], k_rep=1.0, influence_radius=1.0)
    >>> field.force([[0.5, 0.0], [2.0, 0.0]])      # (1/0.5 - 1)/0.5² = 4
    array([[4., 0.],
           [0., 0.]])
    >>> field.potential([[0.5, 0.0]])
    array([0.5])
    """

    k_rep: float = 1.0
    influence_radius: float = 1.0

    # Slot names before 0123de4 (see _restore).
    _renamed_fields = MappingProxyType({"obstacles": "obstacles_xy", "d0": "influence_radius"})
    __setstate__ = _restore

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            obstacles_xy: ArrayLike,
            *,
            k_rep: float = ...,
            influence_radius: float = ...,
        ) -> None: ...

    def __post_init__(self) -> None:
        _PointRepulsion.__post_init__(self)
        object.__setattr__(self, "k_rep", gain(self.k_rep, "k_rep"))
        object.__setattr__(
            self, "influence_radius", length(self.influence_radius, "influence_radius")
        )

    @classmethod
    def _checked(
        cls, obstacles_xy: FloatArray, k_rep: float, influence_radius: float
    ) -> KhatibRepulsion:
        """A repulsion from arguments its caller has checked, without checking them again.

        The controller's constructor path (it builds one every step):
        ``obstacles_xy`` must be a float64 ``(M, 2)`` array of finite values
        within ±1e9 m (stored as a read-only copy), ``k_rep`` and
        ``influence_radius`` floats within their ranges.
        """
        out = object.__new__(cls)
        object.__setattr__(out, "obstacles_xy", _frozen(obstacles_xy))
        object.__setattr__(out, "_kdtree", None)
        object.__setattr__(out, "k_rep", k_rep)
        object.__setattr__(out, "influence_radius", influence_radius)
        return out

    def _reach(self) -> float:
        return self.influence_radius

    def _radial(self, d: FloatArray) -> tuple[FloatArray, FloatArray]:
        # Saturated below MIN_DISTANCE; the potential is +inf on the obstacle only.
        near = np.maximum(d, MIN_DISTANCE)
        excess = 1.0 / near - 1.0 / self.influence_radius
        mag = self.k_rep * excess / (near * near)
        u = np.where(d == 0.0, np.inf, 0.5 * self.k_rep * excess * excess)
        return u, mag


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False, repr=False, kw_only=True)
class PiecewiseRepulsion(_PointRepulsion):
    """Piecewise-linear repulsion of the omnidirectional LiDAR robot, per obstacle point.

    In the paper's symbols, with ``d`` the distance to an obstacle and ``û`` the
    unit vector toward it, the force is ``-δ·û`` for ``d < r``,
    ``-β(s + r - d)·û`` for ``r <= d <= s + r`` and zero beyond. The potential is
    its integral, ``½β·s² + δ(r - d)``, ``½β(s + r - d)²`` and ``0``. The force
    jumps at ``d = r`` unless ``δ = β·s``; on the obstacle itself it is zero.

    Names: ``delta`` is ``δ``, ``beta`` is ``β``, ``obstacle_radius`` is ``r`` and
    ``spread`` is ``s`` (Goodrich's name for the width of the linear zone).

    Parameters
    ----------
    obstacles_xy : array_like, shape (M, 2)
        Obstacle points ``(x, y)`` in metres, ``|x|, |y| <= 1e9``; ``M = 0`` is
        valid (zero field). Stored as a read-only copy.
    delta : float, default 1.0
        Force magnitude ``δ`` inside ``obstacle_radius``, in ``[1e-12, 1e12]``.
    beta : float, default 1.0
        Gain ``β`` of the linear zone, in ``[1e-12, 1e12]``.
    obstacle_radius : float, default 0.0
        Obstacle (or safety) radius ``r`` (m), in ``[0, 1e6]``.
    spread : float, default 1.0
        Width ``s`` of the linear zone (m), in ``[1e-6, 1e6]``.

    Raises
    ------
    ValueError, TypeError
        As :class:`KhatibRepulsion`.

    Examples
    --------
    >>> field = PiecewiseRepulsion([[0.0, 0.0]], delta=5.0, beta=2.0, obstacle_radius=0.5,
    ...                            spread=1.0)
    >>> field.force([[0.2, 0.0], [1.0, 0.0], [2.0, 0.0]])
    array([[5., 0.],
           [1., 0.],
           [0., 0.]])
    """

    delta: float = 1.0
    beta: float = 1.0
    obstacle_radius: float = 0.0
    spread: float = 1.0

    # Slot names before 0123de4 (see _restore).
    _renamed_fields = MappingProxyType(
        {"obstacles": "obstacles_xy", "r": "obstacle_radius", "s": "spread"}
    )
    __setstate__ = _restore

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            obstacles_xy: ArrayLike,
            *,
            delta: float = ...,
            beta: float = ...,
            obstacle_radius: float = ...,
            spread: float = ...,
        ) -> None: ...

    def __post_init__(self) -> None:
        _PointRepulsion.__post_init__(self)
        object.__setattr__(self, "delta", gain(self.delta, "delta"))
        object.__setattr__(self, "beta", gain(self.beta, "beta"))
        object.__setattr__(
            self,
            "obstacle_radius",
            length(self.obstacle_radius, "obstacle_radius", allow_zero=True),
        )
        object.__setattr__(self, "spread", length(self.spread, "spread"))

    def _reach(self) -> float:
        return self.spread + self.obstacle_radius

    def _radial(self, d: FloatArray) -> tuple[FloatArray, FloatArray]:
        r, s = self.obstacle_radius, self.spread
        reach = s + r
        lin = np.clip(reach - d, 0.0, s)
        core = np.maximum(r - d, 0.0)
        u = 0.5 * self.beta * lin * lin + self.delta * core
        mag = np.where(d < r, self.delta, self.beta * lin)
        return u, mag
