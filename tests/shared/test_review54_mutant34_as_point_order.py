"""Review 54 (MUTANT34): ``as_point`` checks a point's shape before its values.

``as_point`` (review 53) gives the checks and messages of
``as_float_array(value, name, shape=(2,))``, with a pose's hint for a length of
3. Its tests gave wrong shapes of finite numbers only, so checking finiteness
first (a pose holding a NaN refused as "must contain only finite values",
without its hint) passed them.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit._shared.validation import as_float_array, as_point
from navkit.planning import FieldDStar

NAN, INF = math.nan, math.inf


def _message(call: object, value: object) -> str:
    with pytest.raises(ValueError) as info:
        call(value, "goal_xy")  # type: ignore[operator]
    return str(info.value)


@pytest.mark.parametrize(
    "value",
    [(NAN, 0.0, 0.0), (0.0, INF, 0.5), [[NAN, 1.0]], (NAN,), [NAN, 1.0, 2.0, 3.0], (NAN, INF)],
)
def test_the_messages_are_those_of_as_float_array(value: object) -> None:
    own = _message(as_point, value)
    general = _message(lambda v, n: as_float_array(v, n, shape=(2,)), value)
    hint = " (a pose [x, y, theta]? pass its [:2])"
    pose = np.shape(value) == (3,)  # type: ignore[call-overload]
    assert own == (general + hint if pose else general)


def test_a_pose_holding_a_nan_is_named_as_a_pose() -> None:
    planner = FieldDStar(np.ones((4, 4)))
    with pytest.raises(ValueError, match=r"got shape \(3,\) \(a pose \[x, y, theta\]\?"):
        planner.plan_world((NAN, 1.0, 0.0), (3.0, 3.0))
