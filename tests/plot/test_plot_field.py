"""plot_field: surfaces, contours and force arrows of potential fields."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from plot_pixels import render

from navkit.planning import (
    ConicAttraction,
    KhatibRepulsion,
    ParaboloidAttraction,
    SampledField,
    sample_field,
)
from navkit.plot import plot_field

pytest.importorskip("matplotlib")

WINDOW = {"xlim": (-2.0, 2.0), "ylim": (-1.0, 1.0), "resolution": 0.1}


def test_a_surface_is_drawn_on_new_3d_axes() -> None:
    ax = plot_field(ParaboloidAttraction((0.5, 0.0)), **WINDOW)
    assert ax.name == "3d"
    assert len(ax.collections) == 1
    assert ax.get_zlabel() == "potential"  # type: ignore[attr-defined]


def test_contours_show_the_minimum_at_the_goal(tmp_path: Path) -> None:
    ax = plot_field(ParaboloidAttraction((1.0, 0.0)), kind="contour", **WINDOW)
    contour = ax.collections[0]
    levels = np.asarray(contour.levels)  # type: ignore[attr-defined]
    assert levels[0] <= 0.0 < levels[-1]
    image, pixel = render(ax, tmp_path)
    cmap = contour.get_cmap()
    # viridis: the lowest potential is dark purple, the highest bright yellow.
    goal = image[tuple(pixel([1.0, 0.0])[0])]
    far = image[tuple(pixel([-1.95, 0.95])[0])]
    assert np.allclose(goal, cmap(0.0)[:3], atol=0.15)
    assert far.sum() > goal.sum() + 0.5


def test_a_sampled_field_is_drawn_as_sampled() -> None:
    sampled = sample_field(ConicAttraction((0.0, 0.0)), resolution=0.25,
                           xlim=(-1.0, 1.0), ylim=(-1.0, 1.0))  # fmt: skip
    ax = plot_field(sampled, kind="contour")
    assert ax.get_xlim()[0] <= -0.875 and ax.get_xlim()[1] >= 0.875


def _ramp(rows: int, cols: int) -> SampledField:
    """A field rising along x and y, ``rows`` × ``cols`` samples 1 m apart."""
    x, y = np.arange(cols) + 0.5, np.arange(rows) + 0.5
    return SampledField(x, y, np.add.outer(y, x), np.zeros((rows, cols, 2)), resolution=1.0)


@pytest.mark.parametrize("cols", [2, 4])
def test_thinned_contours_reach_the_last_sample(cols: int) -> None:
    # 1100 rows are thinned to every third one for drawing: rows 0, 3, ..., 1098
    # and the last, 1099, which a plain [::3] would drop (and two columns would
    # become one, which matplotlib cannot contour).
    field = _ramp(1100, cols)
    ax = plot_field(field, kind="contour")
    assert ax.get_ylim() == (0.5, 1099.5)
    assert ax.get_xlim() == (0.5, cols - 0.5)
    levels = np.asarray(ax.collections[0].levels)  # type: ignore[attr-defined]
    assert levels[-1] >= field.potential.max()


@pytest.mark.parametrize("shape", [(1, 1), (1, 5), (5, 1)])
def test_contours_of_a_field_one_sample_wide_are_refused(shape: tuple[int, int]) -> None:
    with pytest.raises(ValueError, match=r"kind='contour' needs .* 2 × 2 samples"):
        plot_field(_ramp(*shape), kind="contour")
    # A PotentialField sampled in one cell: the same.
    with pytest.raises(ValueError, match="2 × 2"):
        plot_field(ConicAttraction((0.0, 0.0)), kind="contour", xlim=(0.0, 1.0),
                   ylim=(0.0, 1.0), resolution=2.0)  # fmt: skip
    # The other kinds draw it.
    assert len(plot_field(_ramp(*shape), kind="quiver").collections) == 1
    assert len(plot_field(_ramp(*shape)).collections) == 1


def test_quiver_arrows_point_along_the_force_and_are_thinned() -> None:
    goal = ConicAttraction((0.0, 0.0))
    ax = plot_field(goal, kind="quiver", xlim=(-4.0, 4.0), ylim=(-4.0, 4.0), resolution=0.05)
    arrows = ax.collections[0]
    xy = arrows.get_offsets()
    assert len(xy) <= 25 * 25
    u, v = arrows.U, arrows.V  # type: ignore[attr-defined]
    force = goal.force(np.asarray(xy))
    unit = force / np.linalg.norm(force, axis=1, keepdims=True)
    np.testing.assert_allclose(np.column_stack((u, v)), unit, atol=1e-9)


def test_infinite_potentials_are_capped() -> None:
    # +inf is a Khatib obstacle's potential exactly on it.
    field = ParaboloidAttraction((1.0, 0.0)) + KhatibRepulsion([[0.0, 0.0]], influence_radius=1.0)
    smooth = sample_field(field, xlim=(-1.0, 1.0), ylim=(-1.0, 1.0), resolution=0.1)
    potential = np.array(smooth.potential)
    potential[10, 10] = np.inf
    sampled = SampledField(smooth.x, smooth.y, potential, smooth.force, resolution=0.1)
    ax = plot_field(sampled, kind="contour", clip=10.0)
    assert np.isfinite(np.asarray(ax.collections[0].levels)).all()  # type: ignore[attr-defined]
    assert max(ax.collections[0].levels) <= 10.0 + 1e-9  # type: ignore[attr-defined]
    plot_field(sampled)  # a surface without clip: capped at the largest finite value


@pytest.mark.parametrize(
    ("field", "kwargs", "error", "match"),
    [
        ("conic", {"kind": "heatmap"}, ValueError, "kind"),
        ("conic", {"kind": 3}, TypeError, "kind"),
        ("conic", {"xlim": None}, ValueError, "xlim"),
        ("conic", {"resolution": 1e-4}, ValueError, "at most"),
        ("conic", {"clip": float("nan")}, ValueError, "clip"),
        ("sampled", {"resolution": 0.1}, ValueError, "resolution"),
        ("array", {}, TypeError, "field"),
    ],
)
def test_bad_arguments_are_refused(field: object, kwargs: dict, error: type, match: str) -> None:
    conic = ConicAttraction((0.0, 0.0))
    if field == "sampled":
        field = sample_field(conic, resolution=0.5, xlim=(-1, 1), ylim=(-1, 1))
        args = kwargs
    else:
        args = {**WINDOW, **kwargs}
        field = conic if field == "conic" else np.zeros((3, 3))
    with pytest.raises(error, match=match):
        plot_field(field, **args)  # type: ignore[arg-type]


def test_the_axes_must_fit_the_kind() -> None:
    from matplotlib.figure import Figure

    fig = Figure()
    flat, solid = fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2, projection="3d")
    conic = ConicAttraction((0.0, 0.0))
    with pytest.raises(ValueError, match="3-D"):
        plot_field(conic, ax=flat, kind="surface", **WINDOW)
    with pytest.raises(ValueError, match="2-D"):
        plot_field(conic, ax=solid, kind="contour", **WINDOW)
    assert plot_field(conic, ax=solid, **WINDOW) is solid
