"""One vocabulary in estimation: ``DiffOdometry(bits=)`` and ``UpdateResult.status``.

``DiffOdometry(encoder_bits=)`` is now ``bits=``, the name
``kinematics.tick_delta(bits=)`` and ``sim.WheelEncoders(bits=)`` use; the old
keyword and property still work for a release, with a DeprecationWarning.
``UpdateResult`` gains ``status``, the :class:`FusionStatus` that
``FusionResult.status`` holds for a batch.
"""

from __future__ import annotations

import copy
import pickle
import warnings

import numpy as np
import pytest

from navkit.estimation import (
    DiffOdometry,
    ExtendedKalmanFilter,
    FusionStatus,
    MeasurementLog,
    PlanarFusion,
    UpdateResult,
)
from navkit.kinematics import DiffDrive

DRIVE = DiffDrive(track=0.5, wheel_radius=0.1)
# 16-bit counters that wrap between the readings (65000 -> 464 is +1000 ticks).
LEFT = [65000, 464, 1464]
RIGHT = [65000, 400, 1500]


def test_bits_decodes_wrapping_counters_without_warning() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        odo = DiffOdometry(DRIVE, ticks_per_rev=1000, bits=16)
        assert odo.bits == 16 and DiffOdometry(DRIVE, ticks_per_rev=1000).bits is None
        poses = odo.update_batch(LEFT, RIGHT)
        assert "bits=16" in repr(odo)
    # Without the width the wrap reads as a jump of -64536 ticks: far behind.
    unwrapped = DiffOdometry(DRIVE, ticks_per_rev=1000).update_batch(LEFT, RIGHT)
    assert poses[1, 0] > 0.5 > unwrapped[1, 0]


def test_encoder_bits_warns_and_decodes_the_same() -> None:
    new = DiffOdometry(DRIVE, ticks_per_rev=1000, bits=16)
    with pytest.warns(DeprecationWarning, match="encoder_bits is deprecated.*use bits") as rec:
        old = DiffOdometry(DRIVE, ticks_per_rev=1000, encoder_bits=16)
    assert rec[0].filename == __file__
    np.testing.assert_array_equal(old.update_batch(LEFT, RIGHT), new.update_batch(LEFT, RIGHT))
    assert old.bits == 16
    with pytest.warns(DeprecationWarning, match=r"DiffOdometry\.encoder_bits is deprecated") as rec:
        assert old.encoder_bits == 16
    assert rec[0].filename == __file__


def test_both_names_is_a_type_error_and_errors_name_bits() -> None:
    with pytest.raises(TypeError, match="both bits and its old name encoder_bits"):
        DiffOdometry(DRIVE, ticks_per_rev=1000, bits=16, encoder_bits=16)
    with pytest.raises(ValueError, match="bits must be an integer from 2 to 64"):
        DiffOdometry(DRIVE, ticks_per_rev=1000, bits=1)


# UpdateResult.status: the FusionStatus code of an online update (FusionResult.status's
# enum); ``reason`` stays the message.


def test_ekf_update_status_codes() -> None:
    ekf = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))
    H = np.array([[1.0, 0.0]])
    ok = ekf.update([0.5], lambda x: x[:1], H, [[1.0]])
    assert ok.status is FusionStatus.ACCEPTED and ok.reason is None
    gated = ekf.update([10.0], lambda x: x[:1], H, [[1.0]], gate=9.0)
    assert gated.status is FusionStatus.GATED and gated.reason is not None
    assert "gate" in gated.reason
    huge = ekf.update([1e308], lambda x: -x[:1] * 1e300, H, [[1.0]])
    assert huge.status is FusionStatus.OVERFLOW and not huge.accepted


@pytest.mark.parametrize("plain", [True, False])
def test_planar_fusion_online_status_agrees_with_the_batch(plain: bool) -> None:
    # The same log online (plain floats: the fast path; NumPy scalars: the general
    # path) and in one batch: the same code for every row.
    times = [0.1, 0.2, 0.15, 0.3, 0.4]
    speeds = [1.0, 1.0, 1.0, 50.0, 1e300]
    online = PlanarFusion(t0=0.0, gate_probability=0.99)
    codes = []
    for t, v in zip(times, speeds, strict=True):
        args = (t, v) if plain else (np.float64(t), np.float64(v))
        codes.append(online.update_speed(*args, variance=1e-4).status)
    values = np.column_stack([np.zeros(5), speeds, np.zeros((5, 2))])
    observed = np.array([[False, True, False, False]] * 5)
    log = MeasurementLog(np.array(times), values, np.full((5, 4), 1e-4), observed)
    batch = PlanarFusion(t0=0.0, gate_probability=0.99).update_batch(log)
    assert [FusionStatus(int(c)) for c in batch.status] == codes
    assert codes[:3] == [FusionStatus.ACCEPTED, FusionStatus.ACCEPTED, FusionStatus.OUT_OF_ORDER]
    assert set(codes[3:]) == {FusionStatus.GATED, FusionStatus.OVERFLOW}


def test_update_odometry_fast_path_result_is_accepted_and_copies_keep_it() -> None:
    fusion = PlanarFusion(t0=0.0)
    result = fusion.update_odometry(0.1, 1.0, 0.2, v_variance=0.01, omega_variance=0.01)
    assert result.status is FusionStatus.ACCEPTED
    late = fusion.update_odometry(0.05, 1.0, 0.2, v_variance=0.01, omega_variance=0.01)
    assert late.status is FusionStatus.OUT_OF_ORDER
    for original in (result, late):
        for other in (copy.copy(original), copy.deepcopy(original),
                      pickle.loads(pickle.dumps(original))):  # fmt: skip
            assert other.status is original.status
            assert "status=<FusionStatus." in repr(other)


def test_update_result_status_is_checked_and_defaults_from_accepted() -> None:
    residual = np.array([5.0])
    assert UpdateResult(True, 0.1, residual).status is FusionStatus.ACCEPTED
    assert UpdateResult(False, 30.2, residual, "gated").status is None
    assert UpdateResult(False, 30.2, residual, "gated", 1).status is FusionStatus.GATED  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="status must be ACCEPTED exactly when accepted"):
        UpdateResult(False, 30.2, residual, "gated", FusionStatus.ACCEPTED)
    with pytest.raises(ValueError, match="status must be ACCEPTED exactly when accepted"):
        UpdateResult(True, 0.1, residual, None, FusionStatus.GATED)
    with pytest.raises(TypeError, match="status must be a FusionStatus"):
        UpdateResult(False, 30.2, residual, "gated", "GATED")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="status must be a FusionStatus"):
        UpdateResult(False, 30.2, residual, "gated", True)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="status must be a FusionStatus code"):
        UpdateResult(False, 30.2, residual, "gated", 99)  # type: ignore[arg-type]


def test_a_pickle_from_before_status_reads_it_from_accepted() -> None:
    # Slotted dataclasses pickled their four field values as a list.
    for accepted, reason, expected in ((True, None, FusionStatus.ACCEPTED), (False, "x", None)):
        old = object.__new__(UpdateResult)
        old.__setstate__([accepted, 0.5, np.array([0.1]), reason])
        assert old.status is expected
