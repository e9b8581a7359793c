"""A batch row redone after losing definiteness, then a time gap: the filter as online.

Review 40 (mutation testing, MUTANT11; one of review 38's trimmed ``_fusion.py``
mutants that review 39 did not reach). ``update_batch`` redoes a row whose
kernel step lost definiteness in Python and hands the rest of the log back to
``planar_run``, which undoes a ``TIME_GAP`` in its first row from its last output
row: the redone row's estimate is written there first. The covariance's copy
(``out_p[-1] = p``) read as ``out_p[-2] = p`` passed every test; a gap right after
the redone row then left the filter with a stale covariance (the kernel's, from
before the redo). Oracle: the same readings through the online API, where the
redone reading is accepted and each gap raises ``FilterError``, the filter
unchanged (``MeasurementLog``: rows are applied "exactly as in the online API").
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.errors import FilterError
from navkit.estimation import FusionStatus, MeasurementLog, PlanarFusion, _fusion


def _filter() -> PlanarFusion:
    # As review 19's: a speed reading 1e10 s later loses definiteness in the kernel.
    return PlanarFusion([0.0, 0.0, 0.0, 1e3, 0.5, 0.0], P0=np.eye(6), t0=0.0)


def _log(gap: float) -> MeasurementLog:
    return MeasurementLog(
        np.array([1e10, gap, gap]),
        np.array([[0.0, 0.3, 0.0, 0.0], [0.0, 0.3, 0.0, 0.0], [0.1, 0.0, 0.0, 0.0]]),
        np.array([[1.0, 1e-4, 1.0, 1.0], [1.0, 1e-4, 1.0, 1.0], [1e-2, 1.0, 1.0, 1.0]]),
        np.array([[0, 1, 0, 0], [0, 1, 0, 0], [1, 0, 0, 0]], dtype=bool),
    )


def test_the_first_row_is_redone(monkeypatch: pytest.MonkeyPatch) -> None:
    # Without the loaded retry the row stays refused: the batch took the redo path.
    monkeypatch.setattr(_fusion, "_load", lambda buf: None)
    result = _filter().update_batch(_log(1e150))
    assert result.status[0] == FusionStatus.NOT_POSITIVE_DEFINITE


@pytest.mark.parametrize("gap", [1e150, 1e300])
def test_a_gap_after_a_redone_row_keeps_the_redone_estimate(gap: float) -> None:
    batch = _filter()
    result = batch.update_batch(_log(gap))
    assert result.status.tolist() == [
        FusionStatus.ACCEPTED,
        FusionStatus.TIME_GAP,
        FusionStatus.TIME_GAP,
    ]
    online = _filter()
    assert online.update_speed(1e10, 0.3, variance=1e-4).accepted
    for call in (
        lambda: online.update_speed(gap, 0.3, variance=1e-4),
        lambda: online.update_yaw(gap, 0.1, variance=1e-2),
    ):
        with pytest.raises(FilterError, match="time gap"):
            call()
    assert batch.t == online.t == 1e10
    np.testing.assert_array_equal(batch.x, online.x)
    np.testing.assert_array_equal(batch.P, online.P)
    for row in range(3):
        np.testing.assert_array_equal(result.states[row], online.x)
        np.testing.assert_array_equal(result.covariances[row], online.P)
