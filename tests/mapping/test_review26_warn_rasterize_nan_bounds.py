"""rasterize_polygons refuses a geometry with NaN coordinates without a RuntimeWarning too.

The refusal's message shows the geometry's bounds, and shapely 2.0 (navkit's
floor) computing the bounds of such a geometry warns "invalid value
encountered in bounds" (numpy's floating-point warning): the caller got that
warning on top of the ValueError. Later shapely versions do not warn, so this
test fails before the fix only at the floor (``.ci/run``'s oldest run).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable

import numpy as np
import pytest
import shapely
from shapely.geometry import Point, Polygon

from navkit.mapping import rasterize_polygons

NAN = math.nan


@pytest.mark.parametrize(
    "make",
    [
        lambda: Point(NAN, 0.5),
        lambda: Point(0.5, NAN),
        lambda: shapely.LineString([(0.0, 0.0), (1.0, NAN)]),
        lambda: Polygon([(0.0, 0.0), (1.0, 0.0), (NAN, 1.0), (0.0, 1.0)]),
        lambda: shapely.MultiPoint([(0.5, 0.5), (NAN, 1.0)]),
    ],
)
def test_a_nan_geometry_is_refused_with_no_warning(make: Callable[[], shapely.Geometry]) -> None:
    with np.errstate(invalid="ignore"):  # shapely may warn while building them
        geometry = make()
    with (
        warnings.catch_warnings(action="error"),
        pytest.raises(ValueError, match=r"geometries\[0\] has non-finite coordinates"),
    ):
        rasterize_polygons([geometry], bounds=(0, 0, 1, 1), resolution=0.1)
