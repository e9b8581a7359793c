"""A FieldDStar's pickle is the state when ``__getstate__`` ran (review 53, MUTANT33).

2c44fc9 copies every array of the state under the planner's guard, so that a
call starting once ``__getstate__`` returns, while pickle is still writing the
state out, cannot change what is written. Mutants handing pickle the
planner's own arrays (its costs, its heap, its search values) passed every
test: the threads of review 52's stress test rarely land in that window. A
Pickler's ``persistent_id``, called before each object is written, makes the
window certain: it updates the planner's costs and replans as the first
array is reached. (Without the copies, the pickled search of the new costs
beside the old costs found no path, or searched for ever.)
"""

from __future__ import annotations

import io
import pickle

import numpy as np

from navkit.planning import FieldDStar


def _planner() -> FieldDStar:
    rng = np.random.default_rng(3)
    costs = rng.choice([1.0, 2.0, 4.0], size=(12, 12))
    planner = FieldDStar(costs)
    planner.plan((0, 0), (12, 12))
    planner.update_costs([[5, 5], [6, 6]], np.inf)  # a repair pending: the search held
    return planner


class _CallingPickler(pickle.Pickler):
    """Runs ``call`` once, when the first array of the state is about to be written."""

    def __init__(self, file: io.BytesIO, call: object) -> None:
        super().__init__(file, protocol=pickle.HIGHEST_PROTOCOL)
        self._call = call

    def persistent_id(self, obj: object) -> None:
        if isinstance(obj, np.ndarray) and self._call is not None:
            call, self._call = self._call, None
            call()  # type: ignore[operator]
        return None


def _state(planner: FieldDStar) -> tuple[np.ndarray, list[tuple[float, float]], float]:
    path = planner.replan((12, 0))
    return planner.costs, [tuple(p) for p in path.points.tolist()], path.cost


def test_a_call_made_while_pickle_writes_the_state_is_not_in_the_pickle() -> None:
    before = pickle.loads(pickle.dumps(_planner()))
    planner = _planner()

    def call() -> None:
        # Every cost changed, and a search from elsewhere: a search state of the
        # old costs' (values, queue) written over would not find the way on them.
        planner.update_costs([(r, c) for r in range(12) for c in range(12)], 1.0)
        planner.replan((0, 12))

    buffer = io.BytesIO()
    _CallingPickler(buffer, call).dump(planner)
    after = pickle.loads(buffer.getvalue())
    assert (planner.costs == 1.0).all()  # the call ran, while pickle wrote the state
    costs, points, cost = _state(after)
    want_costs, want_points, want_cost = _state(before)
    np.testing.assert_array_equal(costs, want_costs)
    assert points == want_points
    assert cost == want_cost
