"""Review 30 (REGRESS): ``as_time``'s plain-float fast path refuses and reads as before.

``PlanarFusion.predict`` read its time through ``as_time``, whose type tests
(``numbers.Integral`` is an ABC) doubled the call at 99494d3 (0.49 -> 0.98 us a
call). A plain finite float now returns at once; these tests pin that the fast
path keeps the general path's refusals and results.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.estimation import PlanarFusion


@pytest.mark.parametrize("t", [math.nan, math.inf, -math.inf])
def test_a_non_finite_float_time_is_still_refused(t: float) -> None:
    fusion = PlanarFusion(t0=0.0)
    before = fusion._buf.copy()
    with pytest.raises(ValueError, match=r"^t must be finite"):
        fusion.predict(t)
    with pytest.raises(ValueError, match=r"^t0 must be finite"):
        PlanarFusion(t0=t)
    np.testing.assert_array_equal(fusion._buf, before)


def test_a_float_time_predicts_as_the_general_path() -> None:
    # np.float64 is not type float: it goes through time_error and finite_float.
    fast, general = PlanarFusion(t0=0.0), PlanarFusion(t0=np.float64(0.0))
    for k in range(1, 50):
        fast.predict(k * 0.013)
        general.predict(np.float64(k * 0.013))
    assert type(fast.t) is float
    assert fast._buf.tobytes() == general._buf.tobytes()


def test_a_float_subclass_time_takes_the_general_path() -> None:
    class Stamp(float):
        pass

    fusion = PlanarFusion(t0=Stamp(0.0))
    fusion.predict(Stamp(0.5))
    assert type(fusion.t) is float and fusion.t == 0.5
    with pytest.raises(ValueError, match=r"^t must be finite"):
        fusion.predict(Stamp(math.nan))
