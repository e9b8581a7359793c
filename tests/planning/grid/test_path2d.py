"""Path2D, the one result type of every planner, and NoPathError.expanded."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

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
        ({"points": [[1 + 1j, 0.0]]}, TypeError, "points"),
        ({"points": [[True, False]]}, TypeError, "points"),
        ({"frame": ["grid"]}, TypeError, "frame"),
        ({"frame": np.array(["grid", "world"])}, TypeError, "frame"),
        ({"cost": "1.5"}, TypeError, "cost"),
        ({"cost": True}, TypeError, "cost"),
        ({"cost": 1 + 0j}, TypeError, "cost"),
        ({"cost": -1.0}, ValueError, "cost"),
        ({"cost": -math.inf}, ValueError, "cost"),
        ({"length": "2"}, TypeError, "length"),
        ({"length": math.nan}, ValueError, "length"),
    ],
)
def test_invalid_fields(kwargs: dict[str, object], error: type[Exception], message: str) -> None:
    fields: dict[str, object] = {
        "points": [[0.0, 0.0]], "frame": "grid", "cost": 0.0, "length": 0.0, "expanded": 0
    }
    fields.update(kwargs)
    with pytest.raises(error, match=message):
        Path2D(**fields)  # type: ignore[arg-type]


def test_infinite_or_huge_numbers_are_refused() -> None:
    # Issue 12: a record never holds a non-finite number (no planner returns an
    # infinite cost: no path is NoPathError), nor overflows on a huge integer.
    for fields in ({"cost": math.inf}, {"length": math.inf}, {"cost": 10**400},
                   {"length": 10**400}, {"expanded": 10**400}, {"expanded": 2**63}):
        kwargs: dict[str, object] = {"cost": 0.0, "length": 0.0, "expanded": 0, **fields}
        with pytest.raises(ValueError, match=next(iter(fields))):
            Path2D([[0, 0]], "grid", **kwargs)  # type: ignore[arg-type]
    assert Path2D([[0, 0]], "grid", cost=1e308, length=0.0, expanded=2**63 - 1).cost == 1e308


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


def test_records_built_from_lists_copy_and_never_freeze() -> None:
    # Issue 12: records built from lists crashed, and froze the caller's array.
    listed = [[0, 0], [1, 1]]
    path = Path2D(listed, "grid", cost=1, length=np.float32(1.5), expanded=np.int64(2))
    listed[0][0] = 7
    assert path.points.tolist() == [[0.0, 0.0], [1.0, 1.0]]
    assert (path.cost, path.length, path.expanded) == (1.0, 1.5, 2)
    assert type(path.cost) is float and type(path.length) is float
    assert type(path.expanded) is int
    raw = np.array([[0.0, 0.0], [2.0, 2.0]])
    view = raw[::-1]
    p = Path2D(view, "world", cost=np.float64(3.0), length=np.array(2.0), expanded=0)
    assert raw.flags.writeable and view.flags.writeable
    assert not np.shares_memory(p.points, raw)
    with pytest.raises(ValueError):
        p.points[0, 0] = 1.0
    # Planner results are read-only too, and distinct from each other.
    a = astar(np.ones((3, 3)), (0, 0), (2, 2))
    assert not a.points.flags.writeable
    assert not a.cells.flags.writeable


def test_copied_and_unpickled_paths_keep_read_only_points(
    duplicate: Callable[[Path2D], Path2D],
) -> None:
    # pickle and deepcopy rebuild the fields without __post_init__; the copied
    # points array used to come back writable, so the "frozen" path could change.
    for path in (
        Path2D([[0, 0], [1, 1]], "grid", cost=1.5, length=math.sqrt(2), expanded=3),
        astar(np.ones((3, 3)), (0, 0), (2, 2)),
    ):
        twin = duplicate(path)
        assert not twin.points.flags.writeable
        with pytest.raises(ValueError, match="read-only"):
            twin.points[0, 0] = 5.0
        np.testing.assert_array_equal(twin.points, path.points)
        assert (twin.frame, twin.cost, twin.length, twin.expanded) == (
            path.frame,
            path.cost,
            path.length,
            path.expanded,
        )
