"""Plot branches the default suite never ran (coverage review, session 30).

* A colour tuple matplotlib refuses is named in the message as the numbers the
  caller gave: it printed ``(np.float64(1.0), np.float64(0.0))`` (the NumPy
  scalars of the checked array) since NumPy 2 changed their repr.
* Arrows of a field whose forces span more than three decades are coloured on
  a log scale (a repulsion near its obstacle beside almost nothing far away).
* A scene with more than six labelled items gets its legend beside the axes, and
  a figure made here is widened for it; the caller's own figure is not resized.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

pytest.importorskip("matplotlib")
import matplotlib.pyplot as plt
from matplotlib.colors import LogNorm, to_rgba

from navkit.planning import ConicAttraction, KhatibRepulsion
from navkit.plot import plot_field, plot_path, plot_scene
from navkit.sim import Scene


@pytest.mark.parametrize(
    ("color", "shown"),
    [
        ((1, 0), "(1.0, 0.0)"),
        ([2.0, 0.0, 0.0], "(2.0, 0.0, 0.0)"),
        ((0.5, np.float32(1.5), 0), "(0.5, 1.5, 0.0)"),
    ],
)
def test_a_refused_colour_tuple_is_shown_as_plain_numbers(color: Any, shown: str) -> None:
    with pytest.raises(ValueError) as info:
        plot_path([[0.0, 0.0], [1.0, 1.0]], color=color)
    assert str(info.value) == f"color: {shown} is not a matplotlib colour"
    plt.close("all")


def test_an_accepted_colour_tuple_is_drawn_in_that_colour() -> None:
    given = [0.25, np.float64(0.5), 1]
    ax = plot_path([[0.0, 0.0], [1.0, 1.0]], color=given)
    assert tuple(ax.lines[-1].get_color()) == (0.25, 0.5, 1.0)
    assert given == [0.25, 0.5, 1]
    plt.close(ax.figure)


def test_forces_over_three_decades_are_coloured_on_a_log_scale() -> None:
    # The obstacle off the sample lattice: the nearest sample is pushed hard,
    # the far ones barely (magnitudes 0.1 to 1e27).
    field = KhatibRepulsion([[0.05, 0.05]], k_rep=1.0, influence_radius=2.0)
    ax = plot_field(field, kind="quiver", xlim=(-1.0, 1.0), ylim=(-1.0, 1.0), resolution=0.1)
    arrows = ax.collections[0]
    colours = np.asarray(arrows.get_array())
    assert isinstance(arrows.norm, LogNorm)
    assert arrows.norm.vmin == colours.min() > 0.0
    assert arrows.norm.vmax == colours.max() > 1e3 * colours.min()
    assert np.isfinite(colours).all()
    plt.close(ax.figure)
    # A field within three decades keeps the linear scale.
    ax = plot_field(
        ConicAttraction((0.0, 0.0)),
        kind="quiver",
        xlim=(0.5, 1.5),
        ylim=(0.5, 1.5),
        resolution=0.1,
    )
    assert not isinstance(ax.collections[0].norm, LogNorm)
    plt.close(ax.figure)


def _scene(n_paths: int) -> Scene:
    paths = tuple(
        (f"path {k}", np.array([[0.0, float(k)], [3.0, float(k)]])) for k in range(n_paths)
    )
    return Scene("many", paths=paths)


def test_a_long_legend_goes_beside_the_axes_of_a_widened_figure() -> None:
    ax = plot_scene(_scene(4))
    width = ax.figure.get_size_inches()[0]
    assert ax.get_legend().get_bbox_to_anchor().x1 <= ax.bbox.x1  # inside the axes
    plt.close(ax.figure)
    ax = plot_scene(_scene(7))
    legend = ax.get_legend()
    assert [t.get_text() for t in legend.get_texts()] == [f"path {k}" for k in range(7)]
    assert legend.get_bbox_to_anchor().x0 > ax.bbox.x1  # anchored right of the axes
    assert ax.figure.get_size_inches()[0] == pytest.approx(1.6 * width)
    assert ax.figure.get_layout_engine() is not None
    plt.close(ax.figure)


def test_a_long_legend_leaves_the_callers_figure_its_size() -> None:
    fig, ax = plt.subplots(figsize=(4.0, 3.0))
    plot_scene(_scene(7), ax=ax)
    legend = ax.get_legend()
    assert legend is not None and legend.get_bbox_to_anchor().x0 > ax.bbox.x1
    assert tuple(fig.get_size_inches()) == (4.0, 3.0)
    plt.close(fig)


def test_a_colormap_row_is_a_colour() -> None:
    # A row of cmap(values) is an ndarray of 4 floats: a colour, as matplotlib takes it.
    from matplotlib import colormaps

    rows = colormaps["viridis"](np.linspace(0.0, 1.0, 3))
    assert isinstance(rows[1], np.ndarray)
    line = plot_path([[0.0, 0.0], [1.0, 1.0]], color=rows[1]).get_lines()[-1]
    np.testing.assert_allclose(to_rgba(line.get_color()), rows[1])
    with pytest.raises(ValueError, match="color"):
        plot_path([[0.0, 0.0], [1.0, 1.0]], color=rows)  # the whole table: not one colour
