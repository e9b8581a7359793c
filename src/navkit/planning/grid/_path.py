"""The one path result of every navkit planner: :class:`Path2D`."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.frozen import frozen_setattr, reduce_record, restore_read_only
from navkit._shared.grid_coords import round_half_up
from navkit._shared.text import as_text
from navkit._shared.types import FloatArray, IntArray
from navkit._shared.validation import as_float_array, bounded_int, finite_float

__all__ = ["Path2D"]

_FRAMES = ("grid", "world")
_INT64_MAX = 2**63 - 1


@frozen_setattr
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
        Vertices from start to goal (K >= 1), finite. Stored as a read-only
        float64 copy: the caller's array is neither kept nor frozen.
    frame : {"grid", "world"}
        Frame of ``points``.
    cost : float
        Path cost, finite, >= 0: traversal cost × cells for a ``"grid"``
        path, × metres for a ``"world"`` one (so it equals :attr:`length` in
        free space). Planners never return an infinite cost (no path is
        :class:`navkit.NoPathError`).
    length : float
        Length of the polyline: cells (``"grid"``) or metres (``"world"``),
        finite, >= 0.
    expanded : int
        Number of search expansions the planner performed, in ``[0, 2**63 - 1]``.

    Raises
    ------
    ValueError
        Bad shape, non-finite points, unknown frame, a cost or length that is
        negative or not finite, expansions out of range.
    TypeError
        Non-numeric points (strings, complex numbers, booleans), a frame that
        is not a string, a cost or length that is not a real number (or is a
        bool), non-integer ``expanded``.

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

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            points: ArrayLike,
            frame: Literal["grid", "world"],
            cost: float,
            length: float,
            expanded: int,
        ) -> None: ...

    def __post_init__(self) -> None:
        pts = np.array(as_float_array(self.points, "points", shape=(None, 2)), copy=True)
        if pts.shape[0] == 0:
            raise ValueError("points must hold at least one vertex, got shape (0, 2)")
        pts.flags.writeable = False
        frame: Any = self.frame
        if not isinstance(frame, str):
            raise TypeError(f"frame must be 'grid' or 'world', got {type(frame).__name__}")
        # Plain str: an np.str_ printed as np.str_('grid') in the record's repr. Checked
        # as stored: a subclass's own == (case-blind, say) let "GRID" through.
        frame = as_text(frame, "frame")
        if frame not in _FRAMES:
            raise ValueError(f"frame must be 'grid' or 'world', got {frame!r}")
        object.__setattr__(self, "frame", frame)
        cost = _non_negative(self.cost, "cost")
        length = _non_negative(self.length, "length")
        expanded = bounded_int(self.expanded, "expanded", 0, _INT64_MAX)
        object.__setattr__(self, "points", pts)
        object.__setattr__(self, "cost", cost)
        object.__setattr__(self, "length", length)
        object.__setattr__(self, "expanded", expanded)

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

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, ("points",))

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, ``points`` read-only again."""
        restore_read_only(self, state, ("points",))

    @property
    def cells(self) -> IntArray:
        """Cell ``(row, col)`` containing each vertex, int64 (K, 2), read-only.

        Only for a ``"grid"`` path: each coordinate is rounded half up
        (``floor(v + 0.5)``), the cell whose square ``[r-½, r+½) × [c-½, c+½)``
        holds the vertex. For an A* path these are exactly its cells. A
        coordinate beyond ``±2**62`` (far outside every grid) gives ``±2**62``,
        not its own cell, which int64 cannot always hold.

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


def _non_negative(value: Any, name: str) -> float:
    """A finite real number >= 0 as a float; bools, strings, NaN and infinities refused."""
    out = finite_float(value, name)
    if out < 0.0:
        raise ValueError(f"{name} must be >= 0, got {out}")
    return out
