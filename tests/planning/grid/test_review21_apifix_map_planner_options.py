"""MapPlanner reads back every option it was built with (review 21, API consistency).

``robot_radius``, ``inflate_unknown`` and ``planner`` were readable;
``inflation_radius`` and ``unknown_cost`` now are too, resolved as the costs
used them (``inflation_radius=None`` is ``robot_radius``), so a planner built
from the values read back plans on the same costs.
"""

from __future__ import annotations

import copy
import inspect
import math
import pickle
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner


def _grid() -> OccupancyGrid:
    occupied = np.zeros((20, 24), dtype=bool)
    occupied[:14, 11:13] = True
    unknown = np.zeros_like(occupied)
    unknown[15:, 18:] = True  # an unknown corner
    return OccupancyGrid.from_occupancy(occupied, resolution=0.1, unknown=unknown)


def test_every_option_is_readable() -> None:
    planner = MapPlanner(_grid())
    options = [p for p in inspect.signature(MapPlanner).parameters if p != "grid"]
    assert [name for name in options if not hasattr(planner, name)] == []


@settings(max_examples=30, deadline=None)
@given(
    st.floats(0.0, 0.5),
    st.one_of(st.none(), st.floats(0.0, 0.6)),
    st.one_of(st.just(math.inf), st.floats(1.0, 100.0), st.integers(1, 100)),
)
def test_options_read_back_and_rebuild_the_same_costs(
    robot_radius: float, extra: float | None, unknown_cost: float
) -> None:
    inflation = None if extra is None else robot_radius + extra
    planner = MapPlanner(
        _grid(), robot_radius=robot_radius, inflation_radius=inflation, unknown_cost=unknown_cost
    )
    assert planner.inflation_radius == (robot_radius if inflation is None else inflation)
    assert type(planner.inflation_radius) is float
    assert planner.unknown_cost == unknown_cost
    assert type(planner.unknown_cost) is float
    rebuilt = MapPlanner(
        _grid(),
        robot_radius=planner.robot_radius,
        inflation_radius=planner.inflation_radius,
        unknown_cost=planner.unknown_cost,
        inflate_unknown=planner.inflate_unknown,
    )
    assert np.array_equal(rebuilt.costs, planner.costs)


def test_numpy_scalars_read_back_as_floats() -> None:
    planner = MapPlanner(
        _grid(),
        robot_radius=0.1,
        inflation_radius=np.float32(0.25),  # type: ignore[arg-type]
        unknown_cost=np.int64(7),  # type: ignore[arg-type]
    )
    assert (planner.inflation_radius, planner.unknown_cost) == (float(np.float32(0.25)), 7.0)
    assert type(planner.inflation_radius) is float and type(planner.unknown_cost) is float


@pytest.mark.parametrize("name", ["inflation_radius", "unknown_cost"])
def test_read_only(name: str) -> None:
    planner = MapPlanner(_grid(), robot_radius=0.1)
    with pytest.raises(AttributeError):
        setattr(planner, name, 0.5)


@pytest.mark.parametrize(
    "copier", [copy.copy, copy.deepcopy, lambda p: pickle.loads(pickle.dumps(p, protocol=0))]
)
def test_copies_read_back_the_same(copier: object) -> None:
    planner = MapPlanner(_grid(), robot_radius=0.1, inflation_radius=0.3, unknown_cost=20.0)
    twin = copier(planner)  # type: ignore[operator]
    assert (twin.inflation_radius, twin.unknown_cost) == (0.3, 20.0)


def test_a_planner_pickled_with_the_radius_unresolved_reads_it_resolved() -> None:
    # Planners pickled before this review kept inflation_radius as given (None too).
    planner = MapPlanner(_grid(), robot_radius=0.15)
    state: Any = planner.__reduce_ex__(4)[2]
    old = MapPlanner.__new__(MapPlanner)
    old.__setstate__(state)
    assert old.inflation_radius == 0.15
    slots = dict(state[1])
    slots["_inflation_radius"] = 0.4
    old.__setstate__((state[0], slots))
    assert old.inflation_radius == 0.4
