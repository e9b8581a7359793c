"""Items the single-pair fast paths must leave to the general way (review 33, fresh eyes).

``cell_to_world`` and ``world_to_cell(..., continuous=True)`` on one pair read
lists, tuples and (2,) float64 arrays of exact ``float``/``np.float64`` items
(and, for cells, exact ``int`` items within ±2**53) themselves. Anything else must get the general
way's answer or refusal: ``bool`` items (a bool is an ``int``: an ``isinstance``
test would take ``True`` as 1 and answer where the general way refuses),
``int`` subclasses, ``np.int64`` items, a pair of arrays, and results that do
not follow a caller's ``np.seterr``. The oracle is a ``list`` subclass, which
the fast paths never take.
"""

from __future__ import annotations

import enum
import math

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid


class _Listed(list):  # type: ignore[type-arg]
    """A list the fast paths do not take (exact types only): the general way's oracle."""


class _Cell(enum.IntEnum):
    SEVEN = 7


def _outcome(f: object, value: object, **kw: object) -> tuple[str, object]:
    try:
        out = f(value, **kw)  # type: ignore[operator]
    except (TypeError, ValueError) as e:
        return type(e).__name__, str(e)
    if isinstance(out, float):
        return "float", (out, math.copysign(1.0, out))
    assert isinstance(out, np.ndarray)
    return "array", (out.dtype.str, out.shape, out.tobytes())


_GRID = OccupancyGrid.empty(
    width=3.0, height=2.0, resolution=0.05, origin=Pose2D(-1e6, 2.5e5, -2.1)
)

_PAIRS = [
    [True, 0],
    [0.5, False],
    (np.True_, 1.0),
    [np.int64(3), 1],
    [3, np.int32(-4)],
    [_Cell.SEVEN, 2],
    [2**53 + 1, 0],
    [-(2**62), 5],
    [2**62 + 1, 0],
    (np.array([1.0]), np.array([2.0])),
    (np.array(1.0), 2.0),
    [np.float32(0.25), 1.0],
    [-0.0, -0.0],
    [5e-324, -5e-324],
    [math.nan, 1.0],
    [1.0, -math.inf],
]


@pytest.mark.parametrize("pair", _PAIRS, ids=repr)
def test_cell_to_world_one_pair_as_general(pair: list[object]) -> None:
    assert _outcome(_GRID.cell_to_world, pair) == _outcome(_GRID.cell_to_world, _Listed(pair))


@pytest.mark.parametrize("pair", _PAIRS, ids=repr)
def test_world_to_cell_continuous_one_pair_as_general(pair: list[object]) -> None:
    fast = _outcome(_GRID.world_to_cell, pair, continuous=True)
    assert fast == _outcome(_GRID.world_to_cell, _Listed(pair), continuous=True)


def test_bool_cells_refused_named() -> None:
    # The general way's refusal, not the cell (1, 0) read from True.
    with pytest.raises(TypeError, match="cells"):
        _GRID.cell_to_world([True, 0])
    with pytest.raises(TypeError, match="points_xy"):
        _GRID.world_to_cell([0.5, np.True_], continuous=True)


@pytest.mark.parametrize("pair", [[1e-200, 1e-200], [-1e-300, 3.0]], ids=repr)
def test_fast_paths_follow_no_caller_seterr(pair: list[float]) -> None:
    # Tiny normal values: the general way gives NumPy's default answer under any
    # np.seterr (getting-started's policy), so must the plain float arithmetic.
    with np.errstate(all="raise"):
        point = _outcome(_GRID.cell_to_world, pair)
        cont = _outcome(_GRID.world_to_cell, pair, continuous=True)
    assert point == _outcome(_GRID.cell_to_world, _Listed(pair))
    assert cont == _outcome(_GRID.world_to_cell, _Listed(pair), continuous=True)
    assert point[0] == "array" and cont[0] == "array"


def test_oracle_is_the_general_way(monkeypatch: pytest.MonkeyPatch) -> None:
    # The comparisons mean something only if _Listed values do take the general way.
    from navkit.mapping import _grid

    seen: list[object] = []
    general = _grid.as_pairs

    def spy(value: object, name: str) -> tuple[np.ndarray, bool]:
        seen.append(value)
        return general(value, name)  # type: ignore[arg-type]

    monkeypatch.setattr(_grid, "as_pairs", spy)
    _GRID.cell_to_world([1.0, 2.0])
    _GRID.world_to_cell([1.0, 2.0], continuous=True)
    assert seen == []
    _GRID.cell_to_world(_Listed([1.0, 2.0]))
    _GRID.world_to_cell(_Listed([1.0, 2.0]), continuous=True)
    assert len(seen) == 2
