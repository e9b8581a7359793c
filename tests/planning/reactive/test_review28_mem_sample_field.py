"""sample_field holds no grids of points beyond the one it evaluates (review 28)."""

from __future__ import annotations

import numpy as np

from memory_peak import peak_bytes
from navkit.planning import KhatibRepulsion, ParaboloidAttraction, sample_field


def test_sample_field_peak_is_about_twice_its_result() -> None:
    # No obstacles: the field's own work is two zero arrays, so the peak is
    # sample_field's. The meshgrid (two grids of x and y) and the points stacked
    # from it were all alive while SampledField copied the results: 3.3 times
    # the result; the points written in place and dropped before that copy, 2.
    field = KhatibRepulsion(np.empty((0, 2)))
    peak, sampled = peak_bytes(
        lambda: sample_field(field, xlim=(0.0, 40.0), ylim=(-10.0, 10.0), resolution=0.04)
    )
    size = sampled.potential.nbytes + sampled.force.nbytes
    assert sampled.shape == (500, 1000)
    assert peak < 2.5 * size, f"peak {peak / 1e6:.1f} MB for {size / 1e6:.1f} MB of results"


def test_sample_field_points_are_the_grid_centres_in_meshgrid_order() -> None:
    field = ParaboloidAttraction((0.3, -0.7))
    sampled = sample_field(field, xlim=(-1.0, 2.0), ylim=(-2.0, 1.0), resolution=0.25)
    gx, gy = np.meshgrid(sampled.x, sampled.y)
    pts = np.stack((gx.ravel(), gy.ravel()), axis=1)
    assert np.array_equal(sampled.potential, field.potential(pts).reshape(sampled.shape))
    assert np.array_equal(sampled.force, field.force(pts).reshape((*sampled.shape, 2)))
