"""Grid planners pickle without their derived views (session 25, FDPATH).

Pickle stores a view as an array of its own: ``AStarPlanner`` pickled its grid
twice (``_costs`` and the flat view ``_flat``), and ``FieldDStar`` its node
records beside the ``_g`` / ``_rhs`` / heap-slot views of them, and its whole
preallocated heap (a fresh 1000² planner: 80 MB). Checked here: the sizes,
that pickles and copies restore every attribute bit for bit (heap slots a
search left behind included) and continue as the original, and that pickles
made the way earlier versions made them (``__getstate__`` was
:func:`slot_state`: every slot) still load and continue the same.
"""

from __future__ import annotations

import copy
import pickle
from collections.abc import Iterator
from contextlib import contextmanager, suppress
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.typing import NDArray

from navkit._shared.dunders import slot_state
from navkit.errors import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.planning import AStarPlanner, FieldDStar, MapPlanner

SIDE = 200
CELLS = SIDE * SIDE * 8  # bytes of one float64 cost grid
NODES = (SIDE + 1) ** 2
SLACK = 64 * 1024  # everything else a planner holds


def _old_state(obj: object) -> object:
    """The state earlier versions pickled: every slot (no world points given, then)."""
    state: tuple[Any, dict[str, Any]] = slot_state(obj)  # type: ignore[assignment]
    instance, slots = state
    gone = ("_start_xy", "_goal_xy")
    return instance, {name: value for name, value in slots.items() if name not in gone}


@contextmanager
def _old_pickles(cls: type) -> Iterator[None]:
    """Pickle as navkit did before: every slot, views and the whole heap included."""
    mine = cls.__dict__["__getstate__"]
    setattr(cls, "__getstate__", _old_state)  # noqa: B010 - a dunder of the class
    try:
        yield
    finally:
        setattr(cls, "__getstate__", mine)  # noqa: B010


def _size(obj: object, protocol: int = pickle.HIGHEST_PROTOCOL) -> int:
    return len(pickle.dumps(obj, protocol=protocol))


def _same_state(a: Any, b: Any) -> None:
    """Every slot of two planners equal bit for bit (arrays by their bytes)."""
    for name in type(a).__slots__:
        x, y = getattr(a, name), getattr(b, name)
        if isinstance(x, np.ndarray):
            assert x.dtype == y.dtype and x.shape == y.shape, name
            assert x.tobytes() == y.tobytes(), name
        elif isinstance(x, tuple) and x and isinstance(x[0], np.ndarray):
            for i, (u, v) in enumerate(zip(x, y, strict=True)):
                assert u.tobytes() == v.tobytes(), f"{name}[{i}]"
        elif isinstance(x, tuple) and len(x) == 4 and isinstance(x[1], np.ndarray):
            assert x[0] == y[0] and x[1].tobytes() == y[1].tobytes(), name
            assert x[2:] == y[2:], name
        else:
            assert x == y, name


def _views_of_records(planner: FieldDStar) -> None:
    assert np.shares_memory(planner._g, planner._vals)
    assert np.shares_memory(planner._rhs, planner._vals)
    assert np.shares_memory(planner._heap[2], planner._vals)


def test_astar_pickles_its_grid_once() -> None:
    planner = AStarPlanner(np.ones((SIDE, SIDE)))
    assert CELLS < _size(planner) < CELLS + SLACK
    with _old_pickles(AStarPlanner):
        assert _size(planner) > 2 * CELLS  # what it was
    for protocol in range(pickle.HIGHEST_PROTOCOL + 1):
        loaded = pickle.loads(pickle.dumps(planner, protocol=protocol))
        assert np.shares_memory(loaded._flat, loaded._costs)
        assert not loaded._flat.flags.writeable


def test_field_dstar_pickles_no_views_nor_unused_records() -> None:
    costs = np.ones((SIDE, SIDE))
    planner = FieldDStar(costs)
    pad = (SIDE + 2) ** 2 * 8
    assert _size(planner) < pad + SLACK  # a fresh planner: its costs only
    with _old_pickles(FieldDStar):
        old_fresh = _size(planner)
    planner.plan((0, 0), (SIDE, SIDE))
    records = planner._vals.nbytes
    assert _size(planner) < pad + records + SLACK  # + the heap slots a search reached
    with _old_pickles(FieldDStar):
        # g, rhs, the slots, the heap's nodes and keys again: 6 float64 a node more.
        assert _size(planner) > old_fresh > pad + records + (2 + 1 + 1 + 2) * NODES * 8
    grid = OccupancyGrid.from_occupancy(np.zeros((SIDE, SIDE), dtype=bool), resolution=0.05)
    # MapPlanner holds one of them: it shrinks through them, by the flat grid and
    # by the records, views and heap of a fresh Field D* (9 float64 a node).
    with _old_pickles(AStarPlanner), _old_pickles(FieldDStar):
        before = _size(MapPlanner(grid)), _size(MapPlanner(grid, planner="field_dstar"))
    assert _size(MapPlanner(grid)) < before[0] - CELLS + SLACK
    assert _size(MapPlanner(grid, planner="field_dstar")) < before[1] - 9 * NODES * 8 + SLACK


@st.composite
def _grids(draw: st.DrawFn) -> NDArray[np.float64]:
    shape = (draw(st.integers(2, 14)), draw(st.integers(2, 14)))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    return np.asarray(rng.choice([1.0, 3.0, 9.0, np.inf], size=shape), dtype=np.float64)


def _nodes(draw: Any, costs: NDArray[np.float64]) -> tuple[int, int]:
    return (draw(st.integers(0, costs.shape[0])), draw(st.integers(0, costs.shape[1])))


def _replan(planner: FieldDStar) -> tuple[bytes, float] | str:
    try:
        path = planner.replan()
    except (NoPathError, ValueError) as exc:
        return type(exc).__name__ + str(exc)
    return path.points.tobytes(), path.cost


@settings(max_examples=60, deadline=None)
@given(data=st.data(), costs=_grids(), old=st.booleans())
def test_field_dstar_copies_and_pickles_continue_as_the_original(
    data: st.DataObject, costs: NDArray[np.float64], old: bool
) -> None:
    planner = FieldDStar(costs)
    start, goal = _nodes(data.draw, costs), _nodes(data.draw, costs)
    try:
        planner.plan(start, goal)
    except (NoPathError, ValueError):
        return
    rng = np.random.default_rng(data.draw(st.integers(0, 2**32 - 1)))
    for _ in range(data.draw(st.integers(0, 3))):
        cells = np.argwhere(rng.random(costs.shape) < 0.1)
        planner.update_costs(cells, rng.choice([1.0, 2.0, np.inf], size=len(cells)))
        _replan(planner)
    protocol = data.draw(st.integers(0, pickle.HIGHEST_PROTOCOL))
    if old:
        with _old_pickles(FieldDStar):
            twins = [pickle.loads(pickle.dumps(planner, protocol=protocol))]
    else:
        twins = [
            pickle.loads(pickle.dumps(planner, protocol=protocol)),
            copy.copy(planner),
            copy.deepcopy(planner),
        ]
    for twin in twins:
        _same_state(planner, twin)
        _views_of_records(twin)
        assert not np.shares_memory(twin._vals, planner._vals)
        assert not np.shares_memory(twin._pad, planner._pad)
    # The same cost changes and moves: the same paths, bit for bit, apart from each other.
    for _ in range(2):
        cells = np.argwhere(rng.random(costs.shape) < 0.1)
        values = rng.choice([1.0, 2.0, np.inf], size=len(cells))
        move = _nodes(data.draw, costs)
        for p in (planner, *twins):
            p.update_costs(cells, values)
            with suppress(NoPathError, ValueError):
                p.replan(move)
        want = _replan(planner)
        for twin in twins:
            assert _replan(twin) == want
            _same_state(planner, twin)
    # A repeat replan has nothing left to expand: its NoPathError says "expanded 0 nodes"
    # where the one before counted a repair's (a refused move leaves replan() the work).
    again = _replan(planner)
    twins[0].update_costs(np.argwhere(np.isfinite(costs)), np.inf)
    assert _replan(planner) == again  # the original does not see the twin's changes


@pytest.mark.parametrize("protocol", range(pickle.HIGHEST_PROTOCOL + 1))
def test_old_pickles_of_every_state_load(protocol: int) -> None:
    costs = np.ones((12, 15))
    costs[3:9, 7] = np.inf
    planners: list[Any] = [AStarPlanner(costs), FieldDStar(costs, resolution=0.1)]
    world = FieldDStar(costs, resolution=0.1, origin=(0.3, -0.2, 0.0))
    world.plan_world((0.35, 0.05), (1.75, 0.95))
    world.update_costs([(5, 3)], np.inf)
    planners.append(world)
    with _old_pickles(FieldDStar), _old_pickles(AStarPlanner):
        data = pickle.dumps(planners, protocol=protocol)
    astar, fresh, planned = pickle.loads(data)
    _same_state(planners[0], astar)
    assert astar.plan((0, 0), (11, 14)).points.tobytes() == (
        planners[0].plan((0, 0), (11, 14)).points.tobytes()
    )
    _same_state(planners[1], fresh)
    _views_of_records(fresh)
    # Old pickles hold no world points given: their paths end at the nodes' round trip.
    assert planned._start_xy is None and planned._goal_xy is None
    path = planned.replan_world()
    want = world.replan_world()
    assert path.points[1:-1].tobytes() == want.points[1:-1].tobytes()
    # The cost is the node polyline's; the length that of the points (review 54,
    # FOUND7), whose ends differ by the round trip.
    assert path.cost == want.cost
    assert path.length == pytest.approx(want.length, rel=1e-12)
    np.testing.assert_allclose(path.points, want.points, rtol=0, atol=1e-12)
    # Pickled again (now without the views), they load the same.
    again = pickle.loads(pickle.dumps(planned, protocol=protocol))
    _same_state(planned, again)
