"""SampledField / sample_field validation the documentation promises (mutation testing).

Skipping the empty-axis check, the ``-inf`` potential check or accepting a
window with ``max == min`` left every earlier test passing.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.planning import ConicAttraction, SampledField, sample_field


def test_an_empty_axis_is_refused_naming_it() -> None:
    with pytest.raises(ValueError, match=r"^x must hold at least one cell centre"):
        SampledField([], [0.5], np.zeros((1, 0)), np.zeros((1, 0, 2)), resolution=1.0)
    with pytest.raises(ValueError, match=r"^y must hold at least one cell centre"):
        SampledField([0.5], [], np.zeros((0, 1)), np.zeros((0, 1, 2)), resolution=1.0)


@pytest.mark.parametrize("bad", [-math.inf, math.nan])
def test_a_potential_of_minus_inf_or_nan_is_refused(bad: float) -> None:
    # "finite or +inf (a Khatib obstacle); no NaN, no -inf"
    with pytest.raises(ValueError, match="potential must not contain NaN or -inf"):
        SampledField([0.5, 1.5], [0.5], [[1.0, bad]], np.zeros((1, 2, 2)), resolution=1.0)


def test_plus_inf_potential_is_accepted() -> None:
    sampled = SampledField([0.5, 1.5], [0.5], [[1.0, math.inf]], np.zeros((1, 2, 2)),
                           resolution=1.0)
    assert sampled.potential[0, 1] == math.inf


@pytest.mark.parametrize("name", ["xlim", "ylim"])
def test_a_window_of_zero_extent_is_refused(name: str) -> None:
    # "(min, max) extents in metres, max > min": equal limits are no window.
    limits = {"xlim": (0.0, 1.0), "ylim": (0.0, 1.0), name: (0.5, 0.5)}
    with pytest.raises(ValueError, match=rf"^{name} must be \(min, max\) with max > min"):
        sample_field(ConicAttraction((0.0, 0.0)), resolution=0.25, **limits)
