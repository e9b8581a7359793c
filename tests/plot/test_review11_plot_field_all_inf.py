"""plot_field of a potential that is +inf everywhere: refused, not drawn as 0.

``+inf`` potentials (inside obstacles) are drawn at the largest finite one;
with none finite they were drawn at 0: a flat field of potential 0, its colour
bar reading 0, where every point lies inside an obstacle. Surfaces and contours
now need ``clip`` then (drawn at it); arrows (forces are finite) are drawn.
Some +inf among finite potentials keep being drawn at the largest finite one.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.planning import SampledField
from navkit.plot import plot_field

pytest.importorskip("matplotlib")


def _field(potential: np.ndarray) -> SampledField:
    rows, cols = potential.shape
    rng = np.random.default_rng(1)
    force = rng.normal(size=(rows, cols, 2))
    return SampledField(np.arange(cols) * 0.5, np.arange(rows) * 0.5, potential, force,
                        resolution=0.5)  # fmt: skip


@pytest.mark.parametrize("kind", ["surface", "contour"])
def test_an_all_infinite_potential_is_refused_without_clip(kind: str) -> None:
    field = _field(np.full((4, 5), np.inf))
    with pytest.raises(ValueError, match=r"field: every sampled potential is \+inf.*clip"):
        plot_field(field, kind=kind)  # type: ignore[arg-type]


def test_with_clip_an_all_infinite_potential_is_drawn_at_the_cap() -> None:
    field = _field(np.full((4, 5), np.inf))
    ax = plot_field(field, kind="contour", clip=7.0)
    assert np.allclose(ax.collections[0].levels, 7.0)  # type: ignore[attr-defined]
    surface = plot_field(field, kind="surface", clip=7.0)
    low, high = surface.get_zlim()  # type: ignore[attr-defined]
    assert low < 7.0 < high and high - low < 1.0


def test_arrows_of_an_all_infinite_potential_are_drawn() -> None:
    ax = plot_field(_field(np.full((4, 5), np.inf)), kind="quiver")
    assert len(ax.collections) == 1


def test_partly_infinite_potentials_are_still_drawn_at_the_largest_finite() -> None:
    potential = np.arange(20.0).reshape(4, 5)
    potential[1:3, 1:3] = np.inf
    finite_top = float(potential[np.isfinite(potential)].max())
    ax = plot_field(_field(potential), kind="contour")
    levels = np.asarray(ax.collections[0].levels)  # type: ignore[attr-defined]
    assert levels.max() >= finite_top and levels.max() < finite_top + 0.2 * finite_top
    surface = plot_field(_field(potential), kind="surface")
    assert surface.get_zlim()[1] < finite_top * 1.2  # type: ignore[attr-defined]
