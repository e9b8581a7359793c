"""A sampled field's own window corner lies in its cell (0, 0), for any resolution.

``sample_field`` documents that cells start at the window's lower corner
``(xlim[0], ylim[0])`` (and :meth:`SampledField.contains` of that corner is True
in its examples). ``world_to_cell`` used to round ``(p - x[0]) / resolution``
half up, and ``x[0] = xlim[0] + resolution / 2`` is rounded: for most windows
whose resolution is not a power of two (``xlim=(-1, 1)`` at 0.3 m) the corner
itself came out as column -1, outside its own window.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.planning import ConicAttraction, sample_field

FIELD = ConicAttraction(np.zeros(2))


def test_corner_of_a_window_at_0_3_m_is_in_cell_0() -> None:
    sampled = sample_field(FIELD, xlim=(-1.0, 1.0), ylim=(2.0, 3.0), resolution=0.3)
    assert sampled.world_to_cell([-1.0, 2.0]).tolist() == [0, 0]
    assert bool(sampled.contains([-1.0, 2.0]))
    # The far edge stays outside (cells are half-open), the last centre inside.
    assert sampled.world_to_cell([sampled.x[-1], sampled.y[-1]]).tolist() == [3, 6]


@settings(max_examples=60, deadline=None)
@given(
    x0=st.floats(-1e3, 1e3, allow_nan=False),
    y0=st.floats(-1e3, 1e3, allow_nan=False),
    resolution=st.sampled_from([0.3, 0.1, 0.05, 0.03, 0.07, 0.15, 0.7, 1.1, 0.25, 1e-3]),
    cols=st.integers(1, 6),
    rows=st.integers(1, 6),
)
def test_window_corner_and_centres_map_to_their_cells(
    x0: float, y0: float, resolution: float, cols: int, rows: int
) -> None:
    sampled = sample_field(
        FIELD, xlim=(x0, x0 + cols * resolution), ylim=(y0, y0 + rows * resolution),
        resolution=resolution,
    )
    assert sampled.world_to_cell([x0, y0]).tolist() == [0, 0]
    assert bool(sampled.contains([x0, y0]))
    rr, cc = np.mgrid[0 : sampled.shape[0], 0 : sampled.shape[1]]
    centres = np.column_stack((sampled.x[cc.ravel()], sampled.y[rr.ravel()]))
    np.testing.assert_array_equal(
        sampled.world_to_cell(centres), np.column_stack((rr.ravel(), cc.ravel()))
    )
