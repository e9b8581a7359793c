"""plot_field(kind="quiver") keeps whole arrows in view, heads included.

The view was fitted to the sample points only: a small field's edge arrows
ran out of it, and a single sample's arrow (0.8 cells long) was drawn in a
window 0.05 cells wide, its head, the direction, out of sight.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.planning import SampledField
from navkit.plot import plot_field

pytest.importorskip("matplotlib")


@pytest.mark.parametrize("shape", [(1, 1), (2, 2), (1, 4), (60, 3)])
@pytest.mark.parametrize("direction", [(1.0, 0.0), (-0.6, 0.8)])
def test_every_arrow_lies_inside_the_view(
    shape: tuple[int, int], direction: tuple[float, float]
) -> None:
    rows, cols = shape
    resolution = 0.5
    force = np.broadcast_to(np.array(direction) * 3.0, (rows, cols, 2))
    field = SampledField(-2.0 + resolution * (np.arange(cols) + 0.5),
                         1.0 + resolution * (np.arange(rows) + 0.5),
                         np.zeros(shape), force, resolution=resolution)  # fmt: skip
    ax = plot_field(field, kind="quiver")
    ax.figure.canvas.draw()  # the view after the equal-aspect adjustment
    arrows: Any = ax.collections[0]  # a Quiver
    centres = np.asarray(arrows.get_offsets())
    unit = np.column_stack((arrows.U, arrows.V))
    # Arrow length in data units: scale_units="xy", length = |(U, V)| / scale.
    length = np.hypot(unit[:, 0], unit[:, 1]) / arrows.scale
    assert np.allclose(unit, np.array(direction))
    tips = centres + 0.5 * length[:, None] * unit
    tails = centres - 0.5 * length[:, None] * unit
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    for ends in (tips, tails):
        assert np.all((x0 <= ends[:, 0]) & (ends[:, 0] <= x1)), (ends, (x0, x1))
        assert np.all((y0 <= ends[:, 1]) & (ends[:, 1] <= y1)), (ends, (y0, y1))
