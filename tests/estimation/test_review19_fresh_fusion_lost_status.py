"""An interrupt as the online step returns NOT_POSITIVE_DEFINITE leaves a half step (review 19).

``PlanarFusion._settle`` undoes a step whose ``KeyboardInterrupt`` arrived as
the compiled step returned (its status lost, ``status`` still 0) only when the
estimate is not finite: the sign of ``TIME_GAP``. A ``NOT_POSITIVE_DEFINITE``
step leaves the prediction to ``t`` in place (finite), which the uninterrupted
call undoes ("the filter is unchanged"); interrupted there, the filter keeps
it: the time moved to ``t``, neither the estimate from before the call nor the
one after. The session-22 tests made the step *report* ``NOT_POSITIVE_DEFINITE``
and called it "all but unreachable with valid inputs"; it is reached with
ordinary ones (identity covariance, a speed reading 1e10 s later).

Found by a random search over interrupt points (the status is lost at the
``c_return`` after the step); here the interrupt is raised as the real step
returns. Telling NOT_POSITIVE_DEFINITE from a gated or overflowing step (both
also keep the prediction) needs the step's mark in ``buf`` (``BUF_UNDO``, set by
the kernel, cleared by ``undo_step``).
"""

from __future__ import annotations

import contextlib
import copy
from typing import Any

import numpy as np
import pytest

from navkit.errors import FilterError
from navkit.estimation import PlanarFusion, _fusion


def _filter() -> PlanarFusion:
    return PlanarFusion([0.0, 0.0, 0.0, 1e3, 0.5, 0.0], P0=np.eye(6), t0=0.0)


def _estimate(fusion: PlanarFusion) -> tuple[Any, ...]:
    return fusion.t, fusion.x.tobytes(), fusion.P.tobytes()


def _without_loading(monkeypatch: pytest.MonkeyPatch) -> None:
    """Make the loaded retry of a step that lost definiteness fail as the step did.

    Since review 21 such a step is redone from its prediction with the variances
    raised by 2**-40 of themselves, which took every case found; without the
    loading the retry is the step again, and the filter raises as it did here.
    """
    monkeypatch.setattr(_fusion, "_load", lambda buf: None)


@pytest.mark.parametrize("numpy_scalars", [False, True])
def test_not_positive_definite_is_reached_with_ordinary_inputs(
    numpy_scalars: bool, monkeypatch: pytest.MonkeyPatch
) -> None:
    wrap = np.float64 if numpy_scalars else float
    # The kernel's step loses definiteness; the loaded retry takes the reading.
    assert _filter().update_speed(wrap(1e10), wrap(0.3), variance=wrap(1e-4)).accepted
    _without_loading(monkeypatch)
    fusion = _filter()
    before = _estimate(fusion)
    with pytest.raises(FilterError, match="not positive definite"):
        fusion.update_speed(wrap(1e10), wrap(0.3), variance=wrap(1e-4))
    assert _estimate(fusion) == before  # unchanged, as documented


@pytest.mark.parametrize("numpy_scalars", [False, True])
def test_interrupt_as_the_step_returns_leaves_the_filter_unchanged(
    numpy_scalars: bool, monkeypatch: pytest.MonkeyPatch
) -> None:
    real_step = _fusion._step

    def step_then_interrupt(*args: Any) -> Any:
        real_step(*args)  # the step runs; the interrupt lands as it returns
        raise KeyboardInterrupt

    fusion = _filter()
    before = _estimate(fusion)
    wrap = np.float64 if numpy_scalars else float
    monkeypatch.setattr(_fusion, "_step", step_then_interrupt)
    with pytest.raises(KeyboardInterrupt):
        fusion.update_speed(wrap(1e10), wrap(0.3), variance=wrap(1e-4))
    monkeypatch.undo()
    assert _estimate(fusion) == before


def test_interrupted_gated_step_keeps_its_prediction(monkeypatch: pytest.MonkeyPatch) -> None:
    # The outcome the lost status cannot be told from: a gated step keeps the
    # prediction too (and so must stay, interrupted or not).
    real_step = _fusion._step

    def step_then_interrupt(*args: Any) -> Any:
        real_step(*args)
        raise KeyboardInterrupt

    fusion = PlanarFusion([0.0, 0.0, 0.0, 1.0, 0.5, 0.0], t0=0.0, gate_probability=0.99)
    twin = copy.deepcopy(fusion)
    result = twin.update_speed(1.0, 1e6, variance=1e-4)
    assert result.status == _fusion.FusionStatus.GATED
    monkeypatch.setattr(_fusion, "_step", step_then_interrupt)
    with contextlib.suppress(KeyboardInterrupt):
        fusion.update_speed(1.0, 1e6, variance=1e-4)
    monkeypatch.undo()
    assert _estimate(fusion) == _estimate(twin)


def test_the_undo_mark_is_clear_after_every_completed_call(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Set only between a step's return and its undo: a mark left over would make
    # a later interrupted call undo a step that was never its own.
    retried = _filter()
    assert retried.update_speed(1e10, 0.3, variance=1e-4).accepted  # the loaded retry
    assert retried._buf[_fusion.BUF_UNDO] == 0.0
    _without_loading(monkeypatch)
    fusion = _filter()
    with pytest.raises(FilterError, match="not positive definite"):
        fusion.update_speed(1e10, 0.3, variance=1e-4)
    assert fusion._buf[_fusion.BUF_UNDO] == 0.0
    gap = PlanarFusion(P0=np.eye(6), t0=0.0)
    with pytest.raises(FilterError, match="time gap"):
        gap.predict(1e300)
    assert gap._buf[_fusion.BUF_UNDO] == 0.0
    fusion.update_odometry(1.0, 0.5, 0.1, v_variance=1e-4, omega_variance=1e-4)
    fusion.update_yaw(2.0, 0.1, variance=1e-3)
    assert fusion._buf[_fusion.BUF_UNDO] == 0.0
