"""A long-running node's estimators after a refused message and after a reset (review 52, LONGRUN).

A ROS 2 node keeps one filter and one odometry for hours; now and then a
callback hands it a bad message (a NaN stamp, a negative variance, a string, an
overflowing time gap, a counter of the wrong type). The call is refused with a
clear exception, and the object must go on as if the message had never come:
every later call answers bit for bit as a twin's that never saw it. A filter or
odometry reset after a long run answers as a new one built in that state.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.estimation import DiffOdometry, ExtendedKalmanFilter, PlanarFusion
from navkit.kinematics import DiffDrive

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from refused_twin import offer

_BAD = [math.nan, math.inf, -1.0, 1e308, "1.0", None, [1.0, 2.0], np.zeros((2, 2)), 1 + 1j]
_DRIVE = DiffDrive(track=0.4, wheel_radius=0.05)


def _fusion_calls(k: int) -> list[tuple[str, tuple[Any, ...], dict[str, Any]]]:
    """The messages of step ``k`` at 100 Hz: odometry, yaw, yaw rate, speed, acceleration."""
    t = 0.01 * k
    return [
        ("update_odometry", (t, 0.5, 0.1), {"v_variance": 1e-3, "omega_variance": 1e-3}),
        ("update_yaw", (t - 0.004, math.remainder(0.001 * k, math.tau)), {"variance": 1e-3}),
        ("update_yaw_rate", (t, 0.1), {"variance": 1e-3}),
        ("update_speed", (t, 0.5), {"variance": 1e-3}),
        ("update_acceleration", (t, 0.0), {"variance": 1e-3}),
    ]


def _fusion_answers(fusion: PlanarFusion, steps: range) -> list[Any]:
    out: list[Any] = []
    for k in steps:
        for name, args, kwargs in _fusion_calls(k):
            result = getattr(fusion, name)(*args, **kwargs)
            out.append((result.accepted, result.nis, result.residual.tobytes()))
        out.append((fusion.t, fusion.x.tobytes(), fusion.P.tobytes()))
    return out


@pytest.mark.parametrize("history", [0.0, 1.0])
def test_fusion_refusing_bad_messages_goes_on_as_its_twin(history: float) -> None:
    fusion, twin = PlanarFusion(history=history), PlanarFusion(history=history)
    assert _fusion_answers(fusion, range(1, 30)) == _fusion_answers(twin, range(1, 30))
    # Each argument of each message kind in turn, bad, at the next step's stamp.
    refused = 0
    for name, args, kwargs in [*_fusion_calls(30), ("predict", (0.30,), {})]:
        for slot in [*range(len(args)), *kwargs]:
            for bad in _BAD:
                a, kw = list(args), dict(kwargs)
                if isinstance(slot, int):
                    a[slot] = bad
                else:
                    kw[slot] = bad
                refused += offer(
                    lambda f, name=name, a=a, kw=kw: getattr(f, name)(*a, **kw), fusion, twin
                )
    assert refused > 140
    assert fusion.t == twin.t
    assert _fusion_answers(fusion, range(30, 60)) == _fusion_answers(twin, range(30, 60))


@pytest.mark.parametrize("history", [0.0, 1.0])
def test_fusion_reset_after_a_long_run_is_a_new_filter(history: float) -> None:
    fusion = PlanarFusion(history=history)
    _fusion_answers(fusion, range(1, 400))
    x0, p0 = np.array([1.0, -2.0, 0.5, 0.2, 0.0, 0.1]), np.diag([0.1, 0.1, 0.05, 0.2, 0.2, 0.1])
    fusion.reset(x0, p0, t0=0.0)
    new = PlanarFusion(x0, p0, t0=0.0, history=history)
    assert _fusion_answers(fusion, range(1, 60)) == _fusion_answers(new, range(1, 60))


def _ekf_cycle(ekf: ExtendedKalmanFilter, k: int) -> tuple[Any, ...]:
    ekf.predict(lambda x: x + np.array([0.01 * x[1], 0.0]), np.array([[1.0, 0.01], [0.0, 1.0]]),
                np.diag([1e-4, 1e-3]))  # fmt: skip
    result = ekf.update([0.01 * k], lambda x: x[:1], np.array([[1.0, 0.0]]), [[0.05]], gate=9.0)
    return result.accepted, result.nis, ekf.x.tobytes(), ekf.P.tobytes()


def test_ekf_refusing_bad_measurements_goes_on_as_its_twin() -> None:
    ekf = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))
    twin = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))
    assert [_ekf_cycle(ekf, k) for k in range(20)] == [_ekf_cycle(twin, k) for k in range(20)]
    h, jac = (lambda x: x[:1]), np.array([[1.0, 0.0]])
    refused = 0
    for bad in _BAD:
        refused += offer(lambda e, bad=bad: e.update([bad], h, jac, [[0.05]]), ekf, twin)
        refused += offer(lambda e, bad=bad: e.update([0.2], h, jac, [[bad]]), ekf, twin)
        refused += offer(
            lambda e, bad=bad: e.predict(lambda x: x, np.eye(2), np.diag([bad, 1.0])), ekf, twin
        )
    # A measurement of another size (a second sensor) refused for its R only.
    refused += offer(
        lambda e: e.update([0.2, 1.0], lambda x: x, np.eye(2), [[1.0, 2.0], [0.0, 1.0]]), ekf, twin
    )
    assert refused > 20
    assert [_ekf_cycle(ekf, k) for k in range(20, 40)] == [
        _ekf_cycle(twin, k) for k in range(20, 40)
    ]


@pytest.mark.parametrize("bits", [None, 16])
def test_odometry_refusing_bad_counters_goes_on_as_its_twin(bits: int | None) -> None:
    odometry = DiffOdometry(_DRIVE, ticks_per_rev=1000, bits=bits)
    twin = DiffOdometry(_DRIVE, ticks_per_rev=1000, bits=bits)

    def drive(o: DiffOdometry, ks: range) -> list[bytes]:
        return [o.update(37 * k % 65536, 41 * k % 65536).as_array().tobytes() for k in ks]

    assert drive(odometry, range(100)) == drive(twin, range(100))
    refused = 0
    for bad in [*_BAD, 2.5, np.float64(3.0), 2**70]:
        refused += offer(lambda o, bad=bad: o.update(bad, 10), odometry, twin)
        refused += offer(lambda o, bad=bad: o.update(10, bad), odometry, twin)
        refused += offer(lambda o, bad=bad: o.update_batch([100, bad], [120, 130]), odometry, twin)
    assert refused > 30
    assert drive(odometry, range(100, 300)) == drive(twin, range(100, 300))
    # Reset after the long run: as a new odometry at that pose.
    odometry.reset((1.0, 2.0, 0.3))
    new = DiffOdometry(_DRIVE, ticks_per_rev=1000, bits=bits, pose=(1.0, 2.0, 0.3))
    assert drive(odometry, range(300, 400)) == drive(new, range(300, 400))
