"""Late measurements replayed over a step the kernel alone cannot take (review 35, MUTANT4).

With ``history``, a late measurement is fused in stamp order: the steps kept
after it are taken again (``PlanarFusion._rewind``). A kept step whose
compiled update loses definiteness (after weeks without a measurement, review
21) is undone and taken the general way (every variance raised by 2⁻⁴⁰).
Deleting that undo passed the suite: the general way then started from the
failed step's prediction, which gives the same state, but the step was kept
with the prediction as its "before", so a second late measurement between the
two refused as out of order and the filter ended elsewhere. Oracle: the same
measurements in stamp order on a filter without history (the documented
meaning of ``history``).
"""

from __future__ import annotations

import numpy as np

from navkit.estimation import PlanarFusion, _fusion

_X0 = [0.0, 0.0, 0.0, 0.0, 0.01, 0.0]
_GAP = 2e6  # 23 days at the default process noise (test_review21_found_fusion_long_gap)


def _kernel_loses_definiteness(fusion: PlanarFusion, t: float) -> bool:
    first, count, gate, _ = fusion._kinds["yaw"]
    buf = fusion._buf.copy()
    status, _ = _fusion._step(buf, t, first, count, 0.3, 0.0, 1e-4, 1e-4, gate)
    return bool(status == _fusion.NOT_POSITIVE_DEFINITE)


def test_two_late_measurements_before_a_step_taken_the_general_way() -> None:
    ordered = PlanarFusion(_X0, t0=0.0)
    assert ordered.update_yaw_rate(1.0, 0.02, variance=1e-4).accepted
    # Replayed after the first late reading, the yaw step still fails in the kernel.
    assert _kernel_loses_definiteness(ordered, _GAP)
    assert ordered.update_yaw_rate(2.0, 0.03, variance=1e-4).accepted
    assert ordered.update_yaw(_GAP, 0.3, variance=1e-4).accepted

    late = PlanarFusion(_X0, t0=0.0, history=3e6)
    assert late.update_yaw(_GAP, 0.3, variance=1e-4).accepted
    assert late.update_yaw_rate(1.0, 0.02, variance=1e-4).accepted
    assert late.update_yaw_rate(2.0, 0.03, variance=1e-4).accepted
    assert late.t == ordered.t == _GAP
    np.testing.assert_array_equal(late.x, ordered.x)
    np.testing.assert_array_equal(late.P, ordered.P)
