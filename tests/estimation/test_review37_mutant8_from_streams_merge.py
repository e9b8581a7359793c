"""MeasurementLog.from_streams merges long streams with many equal stamps stably (mutation review).

Every earlier test of the merge's order at equal stamps gave fewer than 17 rows, where
NumPy's default sort is an insertion sort and stable anyway: the merge sorted with the
default (unstable) ``np.argsort``, or with its ties reversed, passed them all. Here the
expected log is built row by row in plain Python, sorted by (stamp, the documented kind
order, the row's place in its stream), and compared with the merge bit for bit.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import MeasurementLog

# The documented order at equal stamps, and each stream's column in the log ([θ, v, ω, a]).
_KINDS = ("odometry", "yaw", "yaw_rate", "acceleration")
_COLUMNS = {"yaw": 0, "yaw_rate": 2, "acceleration": 3}


def _streams(rng: np.random.Generator, n: int) -> dict[str, tuple[np.ndarray, ...]]:
    # Stamps from a few values only: long runs of equal stamps within each stream and
    # across the streams, in no order.
    def stamps() -> np.ndarray:
        return rng.integers(0, 6, n).astype(np.float64) * 0.05

    return {
        "odometry": (stamps(), rng.normal(size=n), rng.normal(size=n)),
        "yaw": (stamps(), rng.uniform(-3.0, 3.0, n)),
        "yaw_rate": (stamps(), rng.normal(size=n)),
        "acceleration": (stamps(), rng.normal(size=n)),
    }


def _variances(rng: np.random.Generator, n: int) -> dict[str, object]:
    return {
        "odometry_variance": (rng.uniform(1e-4, 1e-2, n), rng.uniform(1e-4, 1e-2, n)),
        "yaw_variance": rng.uniform(1e-4, 1e-2, n),
        "yaw_rate_variance": rng.uniform(1e-4, 1e-2, n),
        "acceleration_variance": rng.uniform(1e-4, 1e-2, n),
    }


def _expected(
    streams: dict[str, tuple[np.ndarray, ...]], variances: dict[str, object]
) -> tuple[list[float], list[list[float]], list[list[float]], list[list[bool]]]:
    """The merged rows, each built by hand, in (stamp, kind, place in its stream) order."""
    rows = []
    for rank, kind in enumerate(_KINDS):
        if kind not in streams:
            continue
        parts = streams[kind]
        for i, t in enumerate(parts[0].tolist()):
            value = [0.0] * 4
            variance = [1.0] * 4
            seen = [False] * 4
            if kind == "odometry":
                pair = variances["odometry_variance"]
                assert isinstance(pair, tuple)
                for column, part, var in ((1, parts[1], pair[0]), (2, parts[2], pair[1])):
                    value[column] = float(part[i])
                    variance[column] = float(var[i])
                    seen[column] = True
            else:
                column = _COLUMNS[kind]
                var = variances[f"{kind}_variance"]
                assert isinstance(var, np.ndarray)
                value[column] = float(parts[1][i])
                variance[column] = float(var[i])
                seen[column] = True
            rows.append(((t, rank, i), value, variance, seen))
    rows.sort(key=lambda row: row[0])
    return (
        [row[0][0] for row in rows],
        [row[1] for row in rows],
        [row[2] for row in rows],
        [row[3] for row in rows],
    )


def _check(streams: dict[str, tuple[np.ndarray, ...]], variances: dict[str, object]) -> None:
    given = {k: v for k, v in variances.items() if k.removesuffix("_variance") in streams}
    log = MeasurementLog.from_streams(**streams, **given)  # type: ignore[arg-type]
    times, values, var, seen = _expected(streams, variances)
    assert log.times.tolist() == times
    assert log.observed.tolist() == seen
    assert log.values.tolist() == values
    assert log.variances.tolist() == var


def test_long_streams_with_equal_stamps_merge_stably() -> None:
    rng = np.random.default_rng(37)
    for n in (17, 40, 300):
        streams = _streams(rng, n)
        _check(streams, _variances(rng, n))


def test_each_pair_of_streams_keeps_the_documented_order_at_equal_stamps() -> None:
    # Two streams at a time: the kind order holds whichever kinds meet (odometry
    # before yaw before yaw rate before acceleration), each stream's rows in its order.
    rng = np.random.default_rng(8)
    n = 64
    for a in range(4):
        for b in range(a + 1, 4):
            every = _streams(rng, n)
            streams = {_KINDS[a]: every[_KINDS[a]], _KINDS[b]: every[_KINDS[b]]}
            _check(streams, _variances(rng, n))


def test_one_long_stream_of_one_stamp_keeps_its_order() -> None:
    # 200 readings at one stamp (e.g. a replayed burst): the log keeps them as given.
    rng = np.random.default_rng(2)
    n = 200
    yaw = rng.uniform(-3.0, 3.0, n)
    log = MeasurementLog.from_streams(yaw=(np.full(n, 1.5), yaw), yaw_variance=1e-3)
    assert log.values[:, 0].tolist() == yaw.tolist()


@pytest.mark.parametrize("kind", ["yaw", "yaw_rate", "acceleration"])
@pytest.mark.parametrize("shape", [(1,), (2,), (4,), (3, 1)])
def test_a_per_sample_variance_of_another_length_is_refused_naming_it(
    kind: str, shape: tuple[int, ...]
) -> None:
    # One variance per sample or a scalar: a (1,) array is neither (it broadcast to
    # every row, unnoticed, with the shape check deleted), nor a (2,) one for 3 samples.
    stream = (np.array([0.0, 0.1, 0.2]), np.zeros(3))
    message = rf"^{kind}_variance must be a scalar or have shape \(3,\)"
    with pytest.raises(ValueError, match=message):
        MeasurementLog.from_streams(**{kind: stream, f"{kind}_variance": np.full(shape, 1e-3)})


def test_odometry_variances_of_another_length_are_refused_naming_them() -> None:
    odometry = (np.array([0.0, 0.1, 0.2]), np.ones(3), np.zeros(3))
    for which, pair in ((0, (np.full(1, 1e-3), 1e-3)), (1, (1e-3, np.full(2, 1e-3)))):
        with pytest.raises(ValueError, match=rf"^odometry_variance\[{which}\] must be a scalar"):
            MeasurementLog.from_streams(odometry=odometry, odometry_variance=pair)
