"""``MovingObstacle.scripted(loop=...)``'s warning names the ``after`` value to pass.

It said "use after", and ``after=True`` is a ValueError: ``loop=True`` is
``after='loop'`` and ``loop=False`` ``after='stop'``. The test reads the
value from the warning and passes it.
"""

from __future__ import annotations

import ast
import re
import warnings

import numpy as np
import pytest

from navkit.sim import MovingObstacle

PATH = [(0.0, 0.0), (2.0, 0.0)]


@pytest.mark.parametrize("loop", [True, False])
def test_loop_warning_names_the_after_to_pass(loop: bool) -> None:
    with pytest.warns(DeprecationWarning, match="loop is deprecated") as rec:
        old = MovingObstacle.scripted(0.2, PATH, speed=0.5, loop=loop)
    found = re.search(r": use after=(\S+)$", str(rec[0].message))
    assert found, f"the warning names no value for after=: {rec[0].message}"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        new = MovingObstacle.scripted(0.2, PATH, speed=0.5, after=ast.literal_eval(found.group(1)))
    assert new.after == old.after
    for t in (1.0, 5.0, 7.5):
        np.testing.assert_array_equal(new.position_at(t), old.position_at(t))
