"""RangeNoise's absolute term (review 49): the LDS-01's ±15 mm below 0.5 m.

Before review 49 the noise was relative only (``r * (1 + bias + sigma z)``), so a
datasheet's absolute short-range accuracy could only be approximated by a
percentage, which understates it near the sensor (3 % is 3.6 mm at 0.12 m, not
15 mm). ``absolute`` adds ``absolute[b] * z`` with the same draw ``z``: zero by
default, where every reading stays the relative model's to the bit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from shapely.geometry import box

from navkit.sim import Lidar, RangeNoise, World

_INF = math.inf


def _room(half: float) -> World:
    return World(box(-half, -half, half, half).exterior)


def _scan(noise: RangeNoise, world: World, seed: int, *, range_max: float = 3.5) -> np.ndarray:
    lidar = Lidar(n_beams=360, range_min=0.05, range_max=range_max, noise=noise)
    return lidar.scan(world, (0.0, 0.0, 0.0), seed=seed).ranges


def _truth(world: World, *, range_max: float = 3.5) -> np.ndarray:
    return _scan(RangeNoise(limits=(_INF,), sigma=(0.0,)), world, 0, range_max=range_max)


def test_zero_absolute_keeps_every_reading() -> None:
    world = _room(1.0)
    for seed in range(3):
        rel = RangeNoise(limits=(0.5, _INF), sigma=(0.03, 0.05), bias=(0.0, 0.01))
        both = RangeNoise(
            limits=(0.5, _INF), sigma=(0.03, 0.05), bias=(0.0, 0.01), absolute=(0.0, 0.0)
        )
        assert both == rel
        assert np.array_equal(_scan(both, world, seed), _scan(rel, world, seed))


def test_absolute_term_has_its_standard_deviation() -> None:
    # Walls 0.3 to 0.42 m away: all in the absolute band of the LDS-01 model.
    world = _room(0.3)
    lds01 = RangeNoise(limits=(0.5, _INF), sigma=(0.0, 0.05), absolute=(0.015, 0.0))
    truth = _truth(world)
    errors = np.concatenate([_scan(lds01, world, seed) - truth for seed in range(20)])
    assert errors.shape == (7200,)
    assert np.all(np.isfinite(errors))
    # Absolute: the same spread at every range (7200 draws: sd within ~2 % of 15 mm).
    assert 0.0140 < float(np.std(errors)) < 0.0160
    assert abs(float(np.mean(errors))) < 0.001


def test_sizes_share_the_draws() -> None:
    # Common random numbers: doubling the absolute term doubles every error.
    world = _room(1.2)
    truth = _truth(world)
    one = _scan(RangeNoise(limits=(_INF,), sigma=(0.0,), absolute=(0.01,)), world, 7) - truth
    two = _scan(RangeNoise(limits=(_INF,), sigma=(0.0,), absolute=(0.02,)), world, 7) - truth
    np.testing.assert_allclose(two, 2.0 * one, rtol=0, atol=1e-15)
    # And a relative term on top moves each reading by sigma * r times the same z.
    mixed = _scan(RangeNoise(limits=(_INF,), sigma=(0.02,), absolute=(0.01,)), world, 7)
    np.testing.assert_allclose(mixed, truth * (1.0 + 2.0 * one) + one, rtol=0, atol=1e-12)


def test_never_brings_a_wall_beyond_range_max_into_range() -> None:
    # Walls 1.0 to 1.41 m away, range_max 0.9: whatever the noise, nothing in range.
    world = _room(1.0)
    wide = RangeNoise(limits=(_INF,), sigma=(0.0,), absolute=(0.5,))
    for seed in range(5):
        assert np.all(_scan(wide, world, seed, range_max=0.9) == _INF)
    # A wall inside range_max may be carried out (+inf) or below range_min (-inf).
    near = _scan(wide, world, 0, range_max=1.2)
    assert np.any(near == _INF) and np.any(np.isfinite(near))


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"absolute": (-0.001, 0.0)}, ValueError, r"absolute\[0\] must lie in \[0, 1000\] m"),
        ({"absolute": (0.0, 1001.0)}, ValueError, r"absolute\[1\] must lie in \[0, 1000\] m"),
        ({"absolute": (math.nan, 0.0)}, ValueError, r"absolute\[0\]"),
        ({"absolute": (0.01,)}, ValueError, "one entry per band"),
        ({"absolute": "0.01"}, TypeError, "absolute must be a sequence of numbers"),
    ],
)
def test_bad_absolute_is_refused(kwargs: dict[str, object], error: type, match: str) -> None:
    with pytest.raises(error, match=match):
        RangeNoise(limits=(0.5, _INF), sigma=(0.0, 0.05), **kwargs)  # type: ignore[arg-type]


def test_absolute_is_a_tuple_and_the_input_is_kept() -> None:
    given = np.array([0.015, 0.0])
    noise = RangeNoise(limits=(0.5, _INF), sigma=(0.0, 0.05), absolute=given)
    assert noise.absolute == (0.015, 0.0)
    assert type(noise.absolute) is tuple
    assert given.tolist() == [0.015, 0.0]
    assert RangeNoise().absolute == (0.0, 0.0)
