"""The interrupt helpers give back numpy's error state whatever point they interrupt.

``np.errstate.__enter__`` is Python code: an interrupt injected after it set its
context variable, before the ``with`` body, skipped ``__exit__`` and left that state
set for every later test (in the oldest-dependency run a leaked
``np.linalg.cholesky`` callback turned shapely's ``invalid value`` warnings into
``LinAlgError``).
"""

from __future__ import annotations

import numpy as np

from interrupt_points import delivery_points, interrupted_at


def _errstate_call() -> None:
    with np.errstate(over="ignore", invalid="call", call=print):
        np.add(1.0, 2.0)


def test_every_interrupt_point_leaves_numpys_error_state_as_it_was() -> None:
    before = (np.geterr(), np.geterrcall())
    points = delivery_points(_errstate_call)
    assert points >= 2  # errstate's own calls are interrupt points
    raised = 0
    for k in range(1, points + 1):
        raised += interrupted_at(k, _errstate_call)
        assert (np.geterr(), np.geterrcall()) == before, f"interrupted at point {k}"
    assert raised == points


def test_the_suite_starts_each_test_from_numpys_default_error_state() -> None:
    # The autouse fixture in conftest.py restores what a leaking test left.
    assert np.geterrcall() is None
    assert np.geterr() == {"divide": "warn", "over": "warn", "under": "ignore", "invalid": "warn"}
