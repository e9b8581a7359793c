"""Equal Field D* planners pickle to equal bytes (review 18, determinism lens).

``node_records`` (``_dstar_heap``) allocates the heap's node ids and keys with
``np.empty`` and only the slots in use are ever written: a planner's pickle holds the
rest as they were in memory (leftover bytes of the process, pointers and text
included), so two planners built and used alike pickled differently. The unused
slots are now zeros.
"""

from __future__ import annotations

import pickle

import numpy as np

from navkit.planning import FieldDStar


def _used_planner() -> FieldDStar:
    costs = np.ones((20, 20))
    costs[5:15, 10] = np.inf
    planner = FieldDStar(costs)
    planner.plan((0, 0), (20, 20))
    planner.update_costs([(3, 3)], [5.0])
    planner.replan()
    return planner


def test_planners_used_alike_give_the_same_path() -> None:
    # What does hold: the paths (the garbage is never read).
    a, b = _used_planner(), _used_planner()
    assert a.replan().points.tobytes() == b.replan().points.tobytes()
    again = pickle.loads(pickle.dumps(a))
    assert again.replan().points.tobytes() == a.replan().points.tobytes()


def test_planners_used_alike_pickle_to_the_same_bytes() -> None:
    for _ in range(5):  # uninitialised memory may match by chance once; not five times
        a, b = _used_planner(), _used_planner()
        assert pickle.dumps(a) == pickle.dumps(b)
