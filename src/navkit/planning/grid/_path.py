"""The one path result of every navkit planner: :class:`Path2D`."""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from navkit._shared.grid_coords import round_half_up
from navkit._shared.types import FloatArray, IntArray
from navkit._shared.validation import as_float_array

__all__ = ["Path2D"]

_FRAMES = ("grid", "world")


@dataclass(frozen=True, slots=True, eq=False)
class Path2D:
    """A polyline path with its cost, as returned by every planner.

    One type for every planner; ``frame`` says what the points are:

    * ``"grid"``: continuous grid coordinates ``(row, col)`` with integers at
      cell centres (cell ``(r, c)`` covers ``[r-½, r+½) × [c-½, c+½)``). A* paths
      run through cell centres (integer points, see :attr:`cells`); Field D*
      paths through node − 0.5 and points on cell edges.
    * ``"world"``: world points ``(x, y)`` in metres.

    Parameters
    ----------
    points : array_like, shape (K, 2)
        Vertices from start to goal (K >= 1). Stored as a read-only float64 copy.
    frame : {"grid", "world"}
        Frame of ``points``.
    cost : float
        Path cost: traversal cost × cells for a ``"grid"`` path, × metres for a
        ``"world"`` one (so it equals :attr:`length` in free space). NaN is
        rejected; ``inf`` is allowed.
    length : float
        Length of the polyline: cells (``"grid"``) or metres (``"world"``), >= 0.
    expanded : int
        Number of search expansions the planner performed (>= 0).

    Raises
    ------
    ValueError
        Bad shape, non-finite points, unknown frame, NaN cost, negative
        length or expansions.
    TypeError
        Non-numeric points, non-integer ``expanded``.

    Examples
    --------
    >>> path = Path2D([[0, 0], [1, 1], [1, 2]], "grid", cost=2.414, length=2.414, expanded=3)
    >>> path.cells.tolist()
    [[0, 0], [1, 1], [1, 2]]
    >>> path.points.flags.writeable
    False
    """

    points: FloatArray
    frame: Literal["grid", "world"]
    cost: float
    length: float
    expanded: int

    def __post_init__(self) -> None:
        pts = np.array(as_float_array(self.points, "points", shape=(None, 2)), copy=True)
        if pts.shape[0] == 0:
            raise ValueError("points must hold at least one vertex, got shape (0, 2)")
        pts.flags.writeable = False
        if self.frame not in _FRAMES:
            raise ValueError(f"frame must be 'grid' or 'world', got {self.frame!r}")
        cost = float(self.cost)
        if math.isnan(cost):
            raise ValueError("cost must not be NaN")
        length = float(self.length)
        if not length >= 0.0:
            raise ValueError(f"length must be >= 0, got {length}")
        expanded: Any = self.expanded
        if isinstance(expanded, bool) or not isinstance(expanded, numbers.Integral):
            raise TypeError(f"expanded must be an integer, got {type(expanded).__name__}")
        if int(expanded) < 0:
            raise ValueError(f"expanded must be >= 0, got {expanded}")
        object.__setattr__(self, "points", pts)
        object.__setattr__(self, "cost", cost)
        object.__setattr__(self, "length", length)
        object.__setattr__(self, "expanded", int(expanded))

    @classmethod
    def _owned(
        cls,
        points: FloatArray,
        frame: Literal["grid", "world"],
        cost: float,
        length: float,
        expanded: int,
    ) -> Path2D:
        """A path on a fresh float64 (K, 2) array the planner built and hands over.

        Skips the checks and the copy of ``__post_init__`` (which cost more than
        a short prepared A* query itself); only for arrays nobody else refers to,
        which are made read-only here. Every field must already be valid.
        """
        path = object.__new__(cls)
        points.flags.writeable = False
        object.__setattr__(path, "points", points)
        object.__setattr__(path, "frame", frame)
        object.__setattr__(path, "cost", float(cost))
        object.__setattr__(path, "length", float(length))
        object.__setattr__(path, "expanded", int(expanded))
        return path

    @property
    def cells(self) -> IntArray:
        """Cell ``(row, col)`` containing each vertex, int64 (K, 2), read-only.

        Only for a ``"grid"`` path: each coordinate is rounded half up
        (``floor(v + 0.5)``), the cell whose square ``[r-½, r+½) × [c-½, c+½)``
        holds the vertex. For an A* path these are exactly its cells.

        Raises
        ------
        ValueError
            The path is in the ``"world"`` frame.
        """
        if self.frame != "grid":
            raise ValueError(
                "cells is defined for 'grid' paths only; this path is in the 'world' frame "
                "(use OccupancyGrid.world_to_cell(path.points))"
            )
        out: IntArray = round_half_up(self.points)
        out.flags.writeable = False
        return out
