"""Review 19 (FRESH2): a pending-undo mark left set undoes a later, accepted update.

``planar_step`` sets ``BUF_UNDO`` on an online ``TIME_GAP`` / ``NOT_POSITIVE_DEFINITE``
return and only :func:`undo_step` (Python, its last line) clears it. A second Ctrl-C
delivered inside ``undo_step`` after its ``np.copyto`` (the user insists; the first
one arrived as the step returned, so ``_settle`` runs the undo) leaves the filter
restored but the mark set. Nothing clears it afterwards: the next updates are
accepted, and the first interrupt that lands as a later step returns with its status
lost makes ``_settle`` call ``undo_step`` again, which restores ``x``, ``P`` and the
time saved by the last step that *saved* them. An ``INVALID`` step (out of order: the
fast path leaves the checks to the kernel) saves nothing, so an update the caller was
told was accepted disappears. Pickles and copies carry the mark along.

The fix: the kernel clears the mark where the online step saves
``x``, ``P`` and the time (``buf[BUF_UNDO] = 0.0`` after ``buf[BUF_SAVED_TIME] = last``
in ``planar_step``): a set mark then always belongs to the step whose state
``undo_step`` restores, and a stale one undoes nothing that was not undone already.
"""

from __future__ import annotations

import copy
import pickle
from typing import Any

import numpy as np
import pytest

from navkit.estimation import PlanarFusion, _fusion
from navkit.estimation import _fusion_kernels as k


def _filter() -> PlanarFusion:
    return PlanarFusion([0.0, 0.0, 0.0, 1e3, 0.5, 0.0], P0=np.eye(6), t0=0.0)


def _estimate(fusion: PlanarFusion) -> tuple[Any, ...]:
    return fusion.t, fusion.x.tobytes(), fusion.P.tobytes()


def _undo_interrupted_before_the_mark(buf: np.ndarray) -> None:
    """``undo_step`` with a KeyboardInterrupt delivered as its ``np.copyto`` returns."""
    size = k.W * (1 + k.N_STATE)
    buf[k.BUF_TIME] = buf[k.BUF_SAVED_TIME]
    np.copyto(buf[k._X0 : k._X0 + size], buf[k._SAVED0 : k._SAVED0 + size])
    raise KeyboardInterrupt


def _stale_mark(monkeypatch: pytest.MonkeyPatch) -> PlanarFusion:
    """A filter whose NOT_POSITIVE_DEFINITE step was undone with its undo interrupted."""
    fusion = _filter()
    before = _estimate(fusion)
    with monkeypatch.context() as patch:
        patch.setattr(_fusion, "undo_step", _undo_interrupted_before_the_mark)
        with pytest.raises(KeyboardInterrupt):
            fusion.update_speed(1e10, 0.3, variance=1e-4)  # NOT_POSITIVE_DEFINITE
    assert _estimate(fusion) == before  # restored: only the mark is left
    assert fusion._buf[k.BUF_UNDO] != 0.0
    return fusion


def _interrupt_as_an_invalid_step_returns(
    fusion: PlanarFusion, monkeypatch: pytest.MonkeyPatch
) -> None:
    real_step = _fusion._step

    def step_then_interrupt(*args: Any) -> Any:
        status, _ = real_step(*args)
        assert status == k.INVALID
        raise KeyboardInterrupt

    with monkeypatch.context() as patch:
        patch.setattr(_fusion, "_step", step_then_interrupt)
        with pytest.raises(KeyboardInterrupt):
            fusion.update_speed(0.5, 1e3, variance=1e-2)  # older than the filter: INVALID


@pytest.mark.parametrize("carry", ["same", "pickle", "copy"])
def test_an_accepted_update_survives_a_stale_undo_mark(
    carry: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    fusion = _stale_mark(monkeypatch)
    if carry == "pickle":
        fusion = pickle.loads(pickle.dumps(fusion))
    elif carry == "copy":
        fusion = copy.deepcopy(fusion)
    result = fusion.update_speed(1.0, 1e3, variance=1e-2)
    assert result.accepted
    after = _estimate(fusion)
    _interrupt_as_an_invalid_step_returns(fusion, monkeypatch)
    assert _estimate(fusion) == after  # the INVALID step changed nothing; neither may _settle


def test_without_a_stale_mark_the_interrupted_invalid_step_changes_nothing(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    fusion = _filter()
    assert fusion.update_speed(1.0, 1e3, variance=1e-2).accepted
    after = _estimate(fusion)
    assert fusion._buf[k.BUF_UNDO] == 0.0
    _interrupt_as_an_invalid_step_returns(fusion, monkeypatch)
    assert _estimate(fusion) == after
