"""Path2D, the one result type of every planner, and NoPathError.expanded."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from navkit import NavkitError, NoPathError
from navkit.planning import Path2D, astar, field_dstar


def test_points_are_a_read_only_float_copy() -> None:
    raw = np.array([[0, 0], [1, 1], [1, 2]])
    path = Path2D(raw, "grid", cost=2.5, length=1 + math.sqrt(2), expanded=7)
    assert path.points.dtype == np.float64
    assert not path.points.flags.writeable
    assert raw.flags.writeable  # the caller's array is never frozen
    raw[0, 0] = 9
    assert path.points[0, 0] == 0.0
    floats = np.zeros((2, 2))
    assert not np.shares_memory(Path2D(floats, "world", 0.0, 0.0, 0).points, floats)
    assert isinstance(path.cost, float)
    assert isinstance(path.expanded, int)
    with pytest.raises(dataclasses.FrozenInstanceError):
        path.frame = "world"  # type: ignore[misc]
    assert not hasattr(path, "__dict__")


def test_cells_round_half_up_and_only_for_grid_paths() -> None:
    path = Path2D([[-0.5, 0.49], [0.5, 1.5], [2.0, 2.999]], "grid", 1.0, 1.0, 0)
    assert path.cells.tolist() == [[0, 0], [1, 2], [2, 3]]
    assert path.cells.dtype == np.int64
    assert not path.cells.flags.writeable
    world = Path2D([[0.5, 0.5]], "world", 0.0, 0.0, 0)
    with pytest.raises(ValueError, match="world"):
        _ = world.cells


def test_every_grid_planner_returns_a_grid_path2d() -> None:
    costs = np.ones((5, 5))
    a = astar(costs, (0, 0), (4, 4))
    f = field_dstar(costs, (0, 0), (5, 5))
    for path in (a, f):
        assert isinstance(path, Path2D)
        assert path.frame == "grid"
    # Field D* nodes are cell corners: node (i, j) sits at (i - 0.5, j - 0.5),
    # so the corner-to-corner diagonal starts and ends outside the cell centres.
    assert f.points.tolist() == [[-0.5, -0.5], [4.5, 4.5]]
    assert f.cells.tolist() == [[0, 0], [5, 5]]
    assert a.cells.tolist() == [[0, 0], [1, 1], [2, 2], [3, 3], [4, 4]]


@pytest.mark.parametrize(
    ("kwargs", "error", "message"),
    [
        ({"points": np.zeros((0, 2))}, ValueError, "at least one"),
        ({"points": np.zeros((3, 3))}, ValueError, "points"),
        ({"points": np.zeros(2)}, ValueError, "points"),
        ({"points": [[0.0, np.nan]]}, ValueError, "finite"),
        ({"points": [["a", "b"]]}, TypeError, "points"),
        ({"frame": "map"}, ValueError, "frame"),
        ({"cost": math.nan}, ValueError, "cost"),
        ({"length": -1.0}, ValueError, "length"),
        ({"expanded": -1}, ValueError, "expanded"),
        ({"expanded": 1.5}, TypeError, "expanded"),
        ({"expanded": True}, TypeError, "expanded"),
    ],
)
def test_invalid_fields(kwargs: dict[str, object], error: type[Exception], message: str) -> None:
    fields: dict[str, object] = {
        "points": [[0.0, 0.0]], "frame": "grid", "cost": 0.0, "length": 0.0, "expanded": 0
    }
    fields.update(kwargs)
    with pytest.raises(error, match=message):
        Path2D(**fields)  # type: ignore[arg-type]


def test_infinite_cost_is_allowed() -> None:
    assert Path2D([[0, 0]], "grid", cost=math.inf, length=0.0, expanded=0).cost == math.inf


def test_no_path_error_expanded() -> None:
    err = NoPathError("nothing", expanded=12)
    assert isinstance(err, NavkitError)
    assert err.expanded == 12
    assert not hasattr(err, "explored")
    assert NoPathError("default").expanded == 0
    costs = np.ones((3, 3))
    costs[:, 1] = np.inf
    with pytest.raises(NoPathError) as info:
        astar(costs, (0, 0), (2, 2))
    assert info.value.expanded == 3
    with pytest.raises(NoPathError) as info:
        field_dstar(costs, (0, 0), (3, 3))
    assert info.value.expanded > 0
