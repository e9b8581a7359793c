"""Review 51 (MUTANT31): mutants of restore_slots' ``_added_fields`` and its users.

FOUND3's 1c34944 and eeb0ab8 fill the slots a class gained after a release
from the slots an old pickle holds. Mutants of that code which every test
passed, each killed here:

* ``restore_slots`` (and ``OccupancyGrid.__setstate__``) filling the defaults
  also for a state holding no slot: a grid built by ``__new__`` and not filled
  copied before, and then raised ``AttributeError`` (no origin to make its
  floats from). The commit message promises it copies as before.
* ``AStarPlanner``'s ``_lowest`` default taken as the costs' largest, as 1.0
  or 0.5, and its ``_highest`` default dropped: the 908ac92 pickle the tests
  load has costs whose smallest is 1.0 and no query there reads ``_highest``
  (only ``distance_field`` and jump point search do). Here a state without the
  three slots is made from a planner of costs from 2.0 up, and the loaded
  planner must hold a new one's slots and answer ``plan`` and
  ``distance_field`` as it does.
"""

from __future__ import annotations

import copy
import pickle
from types import MappingProxyType
from typing import Any, cast

import numpy as np
import pytest

from navkit._shared.frozen import restore_slots, slot_names
from navkit.mapping import OccupancyGrid
from navkit.planning import AStarPlanner

ADDED = ("_lowest", "_highest", "_jps")


class _Holder:
    __slots__ = ("count", "values")

    _added_fields = MappingProxyType({"count": lambda holder: len(holder.values)})

    def __setstate__(self, state: Any) -> None:
        restore_slots(self, state)


@pytest.mark.parametrize("state", [(None, {}), {}], ids=["tuple", "bare"])
def test_restore_slots_makes_no_default_from_a_state_without_slots(state: Any) -> None:
    empty = object.__new__(_Holder)
    empty.__setstate__(state)  # the default would read ``values``, which is unset
    assert not hasattr(empty, "values") and not hasattr(empty, "count")


@pytest.mark.parametrize(
    "duplicate",
    [copy.copy, copy.deepcopy, lambda grid: pickle.loads(pickle.dumps(grid))],
    ids=["copy", "deepcopy", "pickle"],
)
def test_an_unfilled_grid_copies_as_before(duplicate: Any) -> None:
    empty = OccupancyGrid.__new__(OccupancyGrid)
    try:
        copied = duplicate(empty)
    except AttributeError as exc:
        # Before 1c34944 too, copy.copy of an unfilled grid read its missing log-odds.
        assert duplicate is copy.copy and "_logodds" in str(exc)
        return
    assert type(copied) is OccupancyGrid
    assert not hasattr(copied, "_origin_x") and not hasattr(copied, "_origin_yaw")


def _costs() -> np.ndarray:
    rng = np.random.default_rng(5131)
    costs = 2.0 + rng.integers(0, 4, (7, 9)).astype(np.float64)  # 2.0 .. 5.0, not uniform
    costs[3, 1:7] = np.inf
    costs[5, 4] = np.inf
    return costs


QUERIES = [((0, 0), (6, 8)), ((6, 0), (0, 8)), ((4, 4), (2, 2)), ((0, 8), (6, 2))]


@pytest.mark.parametrize("connectivity", [4, 8])
def test_an_astar_state_without_its_added_slots_loads_as_a_new_planner(connectivity: int) -> None:
    fresh = AStarPlanner(_costs(), connectivity=connectivity)
    instance, slots = cast("tuple[Any, dict[str, Any]]", fresh.__getstate__())
    old_slots = {name: value for name, value in slots.items() if name not in ADDED}
    old = AStarPlanner.__new__(AStarPlanner)
    old.__setstate__((instance, pickle.loads(pickle.dumps(old_slots))))
    assert old.method == fresh.method == "astar" and repr(old) == repr(fresh)
    assert old._lowest == 2.0
    for goal in [(6, 8), (0, 0), (4, 4)]:
        np.testing.assert_array_equal(old.distance_field(goal), fresh.distance_field(goal))
    for start, goal in QUERIES + [(g, s) for s, g in QUERIES]:
        got, want = old.plan(start, goal), fresh.plan(start, goal)
        assert got.cells.tolist() == want.cells.tolist() and got.cost == want.cost
        assert got.expanded == want.expanded
    # Every slot now as a new planner's (``_highest`` found by distance_field).
    for name in slot_names(AStarPlanner):
        if name == "__weakref__":
            continue
        mine, theirs = getattr(old, name), getattr(fresh, name)
        if isinstance(theirs, np.ndarray):
            np.testing.assert_array_equal(mine, theirs)
        else:
            assert mine == theirs, name
