"""Review 53 (FOUND5): a SampledField takes cell-centre axes given as float32.

Centres of a ROS map (or of a float32 array) are each rounded to float32: the
steps between them miss the resolution by up to an ulp of the largest
coordinate (0.72 ulp for 0.01 m from 0), where ``SampledField`` allowed a few
float64 ulps and refused them all as "not evenly spaced". They are accepted
now within 4 ulps of their dtype of evenly spaced centres, where an ulp is at
most 1 % of a cell; axes whose float32 cannot hold a cell's position (0.01 m
cells at 1e4 m) are refused saying to pass float64, and a float32 axis spaced
by another step is refused as before.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.planning import ConicAttraction, SampledField, sample_field


def _record(x: np.ndarray, resolution: float) -> SampledField:
    n = x.shape[0]
    return SampledField(x, [0.5], np.zeros((1, n)), np.zeros((1, n, 2)), resolution=resolution)


@pytest.mark.parametrize("resolution", [0.01, 0.025, 0.03, 0.05, 0.1, 0.3])
@pytest.mark.parametrize("low", [-50.0, -3.0, 0.0, 7.25, 80.0])
def test_float32_centres_are_evenly_spaced(resolution: float, low: float) -> None:
    single = float(np.float32(resolution))
    for n in (2, 10, 1000, 4096):
        for made_at in (resolution, single):
            centres = low + (np.arange(n) + 0.5) * made_at
            x = centres.astype(np.float32)
            for given in (resolution, single):
                sampled = _record(x, given)
                # Read as float64 copies, the float32 values themselves.
                assert sampled.x.dtype == np.float64
                assert np.array_equal(sampled.x, x.astype(np.float64))
                # Each centre lies in its own cell.
                cells = sampled.world_to_cell(np.column_stack((x, np.full(n, 0.5))))
                assert np.array_equal(cells[:, 1], np.arange(n)), (resolution, low, n)


def test_a_map_window_in_float32_is_taken() -> None:
    sampled = sample_field(
        ConicAttraction((0.0, 0.0)), xlim=(0.0, 10.0), ylim=(0.0, 1.0), resolution=0.01
    )
    again = SampledField(
        sampled.x.astype(np.float32),
        sampled.y.astype(np.float32),
        sampled.potential,
        sampled.force,
        resolution=0.01,
    )
    assert again.shape == sampled.shape == (100, 1000)
    np.testing.assert_allclose(again.x, sampled.x, atol=1e-6)


def test_a_float32_axis_of_another_step_is_refused() -> None:
    for step in (0.0101, 0.00999, 0.02):
        x = ((np.arange(500) + 0.5) * step).astype(np.float32)
        with pytest.raises(ValueError, match=r"^x must be evenly spaced by resolution = 0\.01$"):
            _record(x, 0.01)
    # One centre off by a hundredth of a cell.
    x = ((np.arange(500) + 0.5) * 0.01).astype(np.float32)
    x[250] += np.float32(1e-4)
    with pytest.raises(ValueError, match="evenly spaced"):
        _record(x, 0.01)


def test_float32_too_coarse_for_the_cells_is_refused_saying_so() -> None:
    x = (1e4 + (np.arange(10) + 0.5) * 0.01).astype(np.float32)
    with pytest.raises(ValueError) as info:
        _record(x, 0.01)
    message = str(info.value)
    assert message.startswith("x must be evenly spaced by resolution = 0.01 (its float32 values")
    assert "pass float64 coordinates" in message
    # The same centres in float64 are taken.
    assert _record(1e4 + (np.arange(10) + 0.5) * 0.01, 0.01).shape == (1, 10)


def test_float64_axes_keep_their_tolerance() -> None:
    # A float64 axis rounded as float32 would be is no float32 axis: still refused.
    x = ((np.arange(100) + 0.5) * 0.01).astype(np.float32).astype(np.float64)
    with pytest.raises(ValueError, match="evenly spaced"):
        _record(x, 0.01)


def test_the_callers_axis_is_not_modified() -> None:
    x = ((np.arange(50) + 0.5) * 0.05).astype(np.float32)
    before = x.copy()
    sampled = _record(x, 0.05)
    assert np.array_equal(x, before) and x.flags.writeable
    assert not sampled.x.flags.writeable
