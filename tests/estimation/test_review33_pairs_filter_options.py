"""Review 33 (PAIRS): the filters' options met in pairs.

``ExtendedKalmanFilter.update`` keeps the validated ``angle_measurements`` and
``gate`` of each measurement size in a buffer, keyed by the objects passed, so that
a call passing the same objects skips their checks: a cache where two options and
the measurement size meet. Each update of a random sequence (sizes 1 to 3, the
angle indices as the same tuple, a new tuple or a list, gates None, float, int,
huge and the smallest normal) must equal, bit for bit, the update of a fresh
filter built from the state before it (which checks everything).

``PlanarFusion``'s ``gate_probability``, ``t0``, ``pose`` (a start far from the
origin, kept apart) and ``history`` met in pairs: measurements given a little out
of order within ``history`` end as the same measurements in stamp order, online and
through :meth:`~navkit.estimation.PlanarFusion.update_batch`; copies and pickles
made part-way and a :meth:`~navkit.estimation.PlanarFusion.reset` filter go on as
a fresh one. They found nothing: they guard the combinations.
"""

from __future__ import annotations

import copy
import math
import pickle
import random
from typing import Any

import numpy as np
import pytest

from all_pairs import all_pairs
from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter, MeasurementLog, PlanarFusion

_ANGLES = {1: [[], [0]], 2: [[], [0], [1], [0, 1]], 3: [[], [2], [0, 2]]}
# One tuple object per index set: passed again, the filter finds it kept.
_KEPT = {m: [tuple(t) for t in ts] for m, ts in _ANGLES.items()}
_GATES = [None, 0.5, 9.0, 9, 1e300, 2.3e-308]


def _outcome(ekf: ExtendedKalmanFilter, *args: Any, **kwargs: Any) -> tuple[Any, ...]:
    try:
        r = ekf.update(*args, **kwargs)
    except FilterError as exc:
        return ("FilterError", str(exc))
    return (r.accepted, r.nis, r.residual.tolist(), r.reason)


@pytest.mark.parametrize("seed", range(12))
def test_ekf_option_cache_equals_a_fresh_filter(seed: int) -> None:
    rng = np.random.default_rng(seed)
    pick = random.Random(seed)
    ekf = ExtendedKalmanFilter(rng.normal(size=3) * 3, np.diag(rng.uniform(0.1, 2, 3)),
                               angle_states=(2,))  # fmt: skip
    for _ in range(60):
        m = pick.choice([1, 2, 3])
        H = rng.normal(size=(m, 3))
        z = rng.normal(size=m) * 4
        R = np.diag(rng.uniform(0.05, 1, m))
        k = pick.randrange(len(_KEPT[m]))
        form = pick.choice(["kept", "list", "new tuple", "default"])
        kwargs: dict[str, Any] = {}
        if form == "kept":
            kwargs["angle_measurements"] = _KEPT[m][k]
        elif form == "list":
            kwargs["angle_measurements"] = list(_ANGLES[m][k])
        elif form == "new tuple":
            kwargs["angle_measurements"] = tuple(_ANGLES[m][k])  # a new tuple each time
        gate = pick.choice(_GATES)
        if gate is not None or pick.random() < 0.5:
            kwargs["gate"] = gate
        fresh = ExtendedKalmanFilter(ekf.x, ekf.P, angle_states=(2,))
        angles = list(kwargs.get("angle_measurements", ()))
        checked = {**kwargs, "angle_measurements": angles} if angles else kwargs

        def h(x: np.ndarray, H: np.ndarray = H) -> np.ndarray:
            return H @ x

        assert _outcome(ekf, z, h, H, R, **kwargs) == _outcome(fresh, z, h, H, R, **checked)
        assert np.array_equal(ekf.x, fresh.x) and np.array_equal(ekf.P, fresh.P)


_KINDS = ("odometry", "yaw", "yaw_rate", "acceleration")


def _streams(seed: int) -> dict[str, Any]:
    rng = np.random.default_rng(seed)

    def stamps(n: int) -> np.ndarray:
        return np.round(np.sort(rng.uniform(0.0, 2.0, n)), 3)

    t_odo, t_yaw, t_gyro, t_acc = stamps(12), stamps(5), stamps(8), stamps(4)
    if seed % 3 == 0:  # readings of several kinds at one stamp
        t_yaw[1] = t_gyro[2] = t_odo[3]
    v = rng.normal(1.0, 0.3, 12)
    if seed % 2:
        v[5] = 40.0  # an outlier for the gate
    return {
        "odometry": (t_odo, v, rng.normal(0.0, 0.3, 12)),
        "yaw": (t_yaw, rng.uniform(-3.1, 3.1, 5)),
        "yaw_rate": (t_gyro, rng.normal(0.0, 0.3, 8)),
        "acceleration": (t_acc, rng.normal(0.0, 0.5, 4)),
    }


def _events(streams: dict[str, Any]) -> list[tuple[float, str, tuple[float, ...]]]:
    """Every reading in stamp order, at one stamp in from_streams' order of kinds."""
    out = []
    for kind, (t, *values) in streams.items():
        for i, stamp in enumerate(t):
            out.append((float(stamp), kind, tuple(float(v[i]) for v in values)))
    return sorted(out, key=lambda e: (e[0], _KINDS.index(e[1])))


def _feed(fusion: PlanarFusion, events: list[tuple[float, str, tuple[float, ...]]]) -> None:
    for t, kind, values in events:
        if kind == "odometry":
            fusion.update_odometry(t, *values, v_variance=1e-3, omega_variance=1e-3)
        elif kind == "yaw":
            fusion.update_yaw(t, *values, variance=1e-3)
        elif kind == "yaw_rate":
            fusion.update_yaw_rate(t, *values, variance=1e-4)
        else:
            fusion.update_acceleration(t, *values, variance=1e-2)


def _late(events: list[Any], history: float, seed: int) -> list[Any]:
    """Neighbours swapped (each reading then late by less than ``history``), not two
    readings of one kind at one stamp, whose order is their stream's."""
    pick = random.Random(seed)
    out = list(events)
    for i in range(len(out) - 1):
        a, b = out[i], out[i + 1]
        if (
            pick.random() < 0.3
            and b[0] - a[0] <= 0.9 * history
            and not (a[1] == b[1] and a[0] == b[0])
        ):
            out[i], out[i + 1] = b, a
    return out


FUSION_OPTIONS = all_pairs(
    {
        "gate_probability": [None, 0.9, 0.999999],
        "t0": [None, 0.0, -0.5],
        "pose": [None, (5e6, 3e6, 1.0)],
        "history": [0.0, 0.5, 10.0],
    }
)


def _same(a: PlanarFusion, b: PlanarFusion) -> bool:
    return bool(np.array_equal(a.x, b.x) and np.array_equal(a.P, b.P))


def _check_fusion_pairs(options: dict[str, Any], seed: int) -> None:
    kwargs = {k: v for k, v in options.items() if v is not None or k != "pose"}
    streams = _streams(seed)
    in_order = _events(streams)
    given = _late(in_order, options["history"], seed) if options["history"] else in_order
    late = PlanarFusion(**kwargs)
    _feed(late, given)
    ordered = PlanarFusion(**{**kwargs, "history": 0.0})
    _feed(ordered, in_order)
    batch = PlanarFusion(**kwargs)
    batch.update_batch(
        MeasurementLog.from_streams(
            **streams,
            odometry_variance=(1e-3, 1e-3),
            yaw_variance=1e-3,
            yaw_rate_variance=1e-4,
            acceleration_variance=1e-2,
        )
    )
    assert _same(late, ordered)
    assert _same(ordered, batch)
    half = len(given) // 2
    part = PlanarFusion(**kwargs)
    _feed(part, given[:half])
    for twin in (copy.copy(part), copy.deepcopy(part), pickle.loads(pickle.dumps(part))):
        _feed(twin, given[half:])
        assert _same(twin, late)
    # reset() keeps the filter's own gate, process noise and history.
    part.reset(t0=options["t0"], pose=options["pose"])
    _feed(part, given)
    assert _same(part, late)


@pytest.mark.parametrize("options", FUSION_OPTIONS, ids=lambda o: str(FUSION_OPTIONS.index(o)))
def test_fusion_option_pairs_late_ordered_batch_and_copies_agree(options: dict[str, Any]) -> None:
    for seed in range(4):
        _check_fusion_pairs(options, seed)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(4, 30))
def test_fusion_option_pairs_thoroughly(seed: int) -> None:
    for options in FUSION_OPTIONS:
        _check_fusion_pairs(options, seed)


def test_the_far_start_is_a_real_pair() -> None:
    """The pose option is not a no-op in these tests: the far start moves the state."""
    far = PlanarFusion(pose=(5e6, 3e6, 1.0))
    assert math.isclose(far.x[0], 5e6)
