"""sample_field and SampledField: values on the grid, grid⇄world conversions, bad input."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.planning import (
    BlendedAttraction,
    ConicAttraction,
    KhatibRepulsion,
    ParaboloidAttraction,
    SampledField,
    sample_field,
)


def test_paper_sized_map() -> None:
    sampled = sample_field(ParaboloidAttraction((6.0, 6.0)), xlim=(0.0, 12.0), ylim=(0.0, 12.0),
                           resolution=0.01)
    assert sampled.potential.shape == (1200, 1200)
    assert sampled.force.shape == (1200, 1200, 2)
    assert sampled.shape == (1200, 1200)
    assert sampled.x[0] == pytest.approx(0.005) and sampled.x[-1] == pytest.approx(11.995)
    row, col = 123, 987
    expected = ParaboloidAttraction((6.0, 6.0)).potential([sampled.x[col], sampled.y[row]])[0]
    assert sampled.potential[row, col] == pytest.approx(expected, rel=1e-12)


def test_matches_pointwise_evaluation_in_blocks() -> None:
    rng = np.random.default_rng(7)
    obstacles = rng.uniform(-3.0, 3.0, size=(3000, 2))
    field = BlendedAttraction((2.0, -1.0)) + KhatibRepulsion(obstacles, influence_radius=0.4)
    sampled = sample_field(field, xlim=(-3.0, 3.0), ylim=(-2.0, 2.5), resolution=0.05)
    assert sampled.potential.shape == (90, 120)  # 10800 points
    rows = rng.integers(0, 90, 30)
    cols = rng.integers(0, 120, 30)
    pts = np.stack((sampled.x[cols], sampled.y[rows]), axis=1)
    np.testing.assert_allclose(sampled.potential[rows, cols], field.potential(pts), rtol=1e-12)
    np.testing.assert_allclose(sampled.force[rows, cols], field.force(pts), rtol=1e-12,
                               atol=1e-12)
    # cell_to_world gives the points the values were taken at (to rounding).
    cells = np.stack((rows, cols), axis=1)
    np.testing.assert_allclose(sampled.cell_to_world(cells), pts, rtol=0.0, atol=1e-12)
    np.testing.assert_array_equal(sampled.world_to_cell(pts), cells)


def test_conversions_follow_the_occupancy_grid_convention() -> None:
    sampled = sample_field(ConicAttraction((0.0, 0.0)), xlim=(-1.0, 1.0), ylim=(2.0, 3.0),
                           resolution=0.25)
    assert sampled.shape == (4, 8)
    # Cell (r, c) covers [r - ½, r + ½) × [c - ½, c + ½): the window's lower-left corner is
    # (-½, -½), its centre cell (0, 0) sits at (x[0], y[0]).
    np.testing.assert_allclose(sampled.cell_to_world([-0.5, -0.5]), [-1.0, 2.0])
    np.testing.assert_allclose(sampled.cell_to_world([3.5, 7.5]), [1.0, 3.0])
    np.testing.assert_allclose(sampled.cell_to_world([2, 5]), [sampled.x[5], sampled.y[2]],
                               rtol=0.0, atol=1e-12)
    np.testing.assert_allclose(sampled.world_to_cell([-1.0, 2.0], continuous=True), [-0.5, -0.5])
    # A point on a cell boundary belongs to the upper cell (round half up).
    np.testing.assert_array_equal(sampled.world_to_cell([-1.0, 2.0]), [0, 0])
    np.testing.assert_array_equal(sampled.world_to_cell([-0.75, 2.25]), [1, 1])
    # Not clipped: outside points give outside indices, and contains says so.
    np.testing.assert_array_equal(sampled.world_to_cell([[5.0, 0.0]]), [[-8, 24]])
    np.testing.assert_array_equal(
        sampled.contains([[0.0, 2.5], [5.0, 0.0], [1.0, 2.5], [-1.0, 2.0]]),
        [True, False, False, True],
    )
    assert sampled.contains([0.0, 2.5]).shape == ()


def test_conversion_shapes() -> None:
    sampled = sample_field(ConicAttraction((0.0, 0.0)), xlim=(0.0, 1.0), ylim=(0.0, 1.0),
                           resolution=0.5)
    assert sampled.world_to_cell([0.1, 0.2]).shape == (2,)
    assert sampled.world_to_cell([0.1, 0.2]).dtype == np.int64
    assert sampled.world_to_cell([[0.1, 0.2]]).shape == (1, 2)
    assert sampled.world_to_cell(np.zeros((5, 2)), continuous=True).dtype == np.float64
    assert sampled.world_to_cell(np.empty((0, 2))).shape == (0, 2)
    assert sampled.cell_to_world([0, 1]).shape == (2,)
    assert sampled.cell_to_world([[0, 1], [1, 1]]).shape == (2, 2)


@settings(max_examples=40)
@given(st.floats(-50.0, 50.0), st.floats(-50.0, 50.0), st.floats(0.01, 2.0),
       st.integers(1, 40), st.integers(1, 40), st.floats(-1.0, 1.0), st.floats(-1.0, 1.0))
def test_world_and_cell_round_trip(
    x0: float, y0: float, res: float, w: int, h: int, fr: float, fc: float
) -> None:
    sampled = sample_field(ConicAttraction((0.0, 0.0)), xlim=(x0, x0 + w * res),
                           ylim=(y0, y0 + h * res), resolution=res)
    cont = np.array([[fr * h, fc * w]])
    back = sampled.world_to_cell(sampled.cell_to_world(cont), continuous=True)
    np.testing.assert_allclose(back, cont, atol=1e-9 * (1.0 + 50.0 / res))
    cells = np.array([[sampled.shape[0] - 1, 0], [0, sampled.shape[1] - 1]])
    np.testing.assert_array_equal(sampled.world_to_cell(sampled.cell_to_world(cells)), cells)


test_world_and_cell_round_trip_thoroughly = slow_twin(
    test_world_and_cell_round_trip, max_examples=100
)


def test_sampled_field_is_frozen_and_copies() -> None:
    x = np.array([0.5, 1.5])
    potential = np.array([[1.0, 2.0]])
    force = np.zeros((1, 2, 2))
    with pytest.raises(TypeError, match="positional"):
        SampledField(x, [0.5], potential, force, 1.0)  # type: ignore[misc]
    sampled = SampledField(x, [0.5], potential, force, resolution=1.0)
    x[0] = 9.0
    potential[0, 0] = 9.0
    assert sampled.x[0] == 0.5 and sampled.potential[0, 0] == 1.0
    assert x.flags.writeable and potential.flags.writeable
    for name in ("x", "y", "potential", "force"):
        with pytest.raises(ValueError, match="read-only"):
            getattr(sampled, name)[0] = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        sampled.resolution = 2.0  # type: ignore[misc]



def test_copied_and_unpickled_sampled_fields_stay_read_only(
    duplicate: Callable[[SampledField], SampledField],
) -> None:
    sampled = sample_field(ConicAttraction((0.0, 0.0)), xlim=(-1.0, 1.0), ylim=(0.0, 1.0),
                           resolution=0.5)
    copy = duplicate(sampled)
    for name in ("x", "y", "potential", "force"):
        np.testing.assert_array_equal(getattr(copy, name), getattr(sampled, name))
        with pytest.raises(ValueError, match="read-only"):
            getattr(copy, name)[0] = 1.0
    assert copy.resolution == sampled.resolution

@pytest.mark.parametrize(
    ("build", "match"),
    [
        (lambda: sample_field(ConicAttraction((0.0, 0.0)), xlim=(1.0, 0.0), ylim=(0.0, 1.0),
                              resolution=0.1), "xlim"),
        (lambda: sample_field(ConicAttraction((0.0, 0.0)), xlim=(0.0, 1.0), ylim=(0.0, math.inf),
                              resolution=0.1), "ylim"),
        (lambda: sample_field(ConicAttraction((0.0, 0.0)), xlim=(0.0, 1.0), ylim=(0.0, 1.0),
                              resolution=0.0), "resolution"),
        (lambda: SampledField([0.5, 1.7], [0.5], [[1.0, 2.0]], np.zeros((1, 2, 2)),
                              resolution=1.0), "x must be evenly spaced"),
        (lambda: SampledField([0.5, 1.5], [0.5], [[1.0, 2.0, 3.0]], np.zeros((1, 2, 2)),
                              resolution=1.0), "potential"),
        (lambda: SampledField([0.5, 1.5], [0.5], [[1.0, 2.0]], np.zeros((1, 2)),
                              resolution=1.0), "force"),
        (lambda: SampledField([], [0.5], [[1.0, 2.0]], np.zeros((1, 2)), resolution=1.0), "x"),
        (lambda: sample_field(ConicAttraction((0.0, 0.0)), xlim=(0.0, 1.0), ylim=(0.0, 1.0),
                              resolution=0.5).world_to_cell([[1.0, 2.0, 3.0]]), "points_xy"),
        (lambda: sample_field(ConicAttraction((0.0, 0.0)), xlim=(0.0, 1.0), ylim=(0.0, 1.0),
                              resolution=0.5).cell_to_world([math.nan, 0.0]), "cells"),
    ],
)
def test_bad_input_raises_naming_the_argument(build: object, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        build()  # type: ignore[operator]


def test_options_are_keyword_only_and_field_is_checked() -> None:
    field = ConicAttraction((0.0, 0.0))
    with pytest.raises(TypeError, match="positional"):
        sample_field(field, (0.0, 1.0), (0.0, 1.0), 0.1)  # type: ignore[misc]
    with pytest.raises(TypeError, match="field"):
        sample_field("not a field", xlim=(0.0, 1.0), ylim=(0.0, 1.0),  # type: ignore[arg-type]
                     resolution=0.1)


@pytest.mark.parametrize(
    ("xlim", "resolution", "cells"),
    [
        ((5000000.1, 5000000.2), 0.01, 10),  # UTM eastings/northings
        ((1000000.2, 1000000.3), 0.01, 10),
        ((100000.4, 100000.6), 0.01, 20),
        ((1000.3, 1000.7), 1e-5, 40000),
        ((0.0, 12.0), 0.01, 1200),
        ((0.0, 12.001), 0.01, 1201),  # a tenth of a cell more gains a cell
    ],
)
def test_exact_multiples_far_from_the_origin_gain_no_cell(
    xlim: tuple[float, float], resolution: float, cells: int
) -> None:
    # In decimal the window is `cells` cells wide; as floats, lo and hi are rounded by up
    # to half an ulp each (1e-8 of a cell at 1e6 m and 1 cm), which is no extra cell.
    sampled = sample_field(ConicAttraction((0.0, 0.0)), xlim=xlim, ylim=(0.0, resolution),
                           resolution=resolution)
    assert sampled.shape == (1, cells)
    assert sampled.x[-1] - resolution / 2 < xlim[1]  # the last cell starts inside


def test_axis_spacing_is_checked_at_utm_offsets() -> None:
    x = 5e6 + 0.025 + 0.05 * np.arange(3)  # spaced by 5 cm, 5000 km from the origin
    values = (np.zeros((1, 3)), np.zeros((1, 3, 2)))
    with pytest.raises(ValueError, match="x must be evenly spaced"):
        SampledField(x, [0.5], *values, resolution=0.052)
    with pytest.raises(ValueError, match="y must be evenly spaced"):
        SampledField([0.5], x, values[0].T, np.zeros((3, 1, 2)), resolution=0.052)
    sampled = SampledField(x, [0.5], *values, resolution=0.05)
    np.testing.assert_array_equal(sampled.world_to_cell([x[2], 0.5]), [0, 2])
    # sample_field's own axes pass at any offset and resolution in range.
    for lo, res in ((-1e9, 1e-6), (5e6 + 0.3, 0.01), (999999.123, 1e6), (1e8, 1e-3)):
        centres = lo + (np.arange(500) + 0.5) * res
        SampledField(centres, [0.5], np.zeros((1, 500)), np.zeros((1, 500, 2)), resolution=res)
