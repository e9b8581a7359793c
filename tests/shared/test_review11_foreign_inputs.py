"""Array-likes from the wider ecosystem (review 11): masked scalars, memoryviews, views.

Masked scalars (``np.ma.masked``, an element of a masked array) were read as
their data by every scalar argument, and 2-D memoryviews made ``(row, col)``
cells and sequences raise Python's ``NotImplementedError``; broadcast and
reversed 1-D views gave products that differ in the last bits from the same
values in a plain array.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit._shared.validation import (
    as_cell,
    as_float_array,
    as_sequence,
    finite_float,
    unpack,
)
from navkit.geometry import Pose2D, Twist2D, integrate
from navkit.mapping import LaserScan, OccupancyGrid, integrate_scan
from navkit.planning import astar

MASKED_SCALARS = [
    pytest.param(np.ma.masked, id="np.ma.masked"),
    pytest.param(np.ma.masked_array(0.5, mask=True), id="0-d masked"),
    pytest.param(np.ma.masked_invalid([1.0, np.nan])[1], id="element of a masked array"),
]


@pytest.mark.parametrize("value", MASKED_SCALARS)
def test_a_masked_scalar_is_refused_naming_the_argument(value: object) -> None:
    with pytest.raises(ValueError, match=r"^dt has masked entries.*filled"):
        finite_float(value, "dt")


def test_a_masked_scalar_without_a_mask_is_its_value() -> None:
    assert finite_float(np.ma.masked_array(0.25), "dt") == 0.25


@pytest.mark.parametrize("value", MASKED_SCALARS)
def test_public_scalar_arguments_refuse_masked_scalars(value: object) -> None:
    with pytest.raises(ValueError, match=r"^dt has masked entries"):
        integrate(Pose2D(0.0, 0.0, 0.0), Twist2D(1.0, 0.0, 0.0), value)  # type: ignore[arg-type]


def test_a_clamp_pair_with_a_masked_bound_is_refused() -> None:
    grid = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.1)
    scan = LaserScan([0.3, 0.3], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0)
    clamp = np.ma.array([-5.0, 5.0], mask=[True, False])
    with pytest.raises(ValueError, match=r"^clamp\[0\] has masked entries"):
        integrate_scan(grid, scan, (0.5, 0.5, 0.0), clamp=clamp)  # type: ignore[arg-type]


MEMORYVIEW_2D = np.zeros((2, 2)).data


def test_a_two_d_memoryview_cell_is_a_type_error() -> None:
    # Python cannot iterate a 2-D memoryview (NotImplementedError): read as its array.
    with pytest.raises(TypeError, match=r"^start must hold integers"):
        as_cell(MEMORYVIEW_2D, "start", (5, 5))
    with pytest.raises(TypeError, match=r"^start_cell must hold integers"):
        astar(np.ones((5, 5)), MEMORYVIEW_2D, (4, 4))


def test_a_one_d_memoryview_cell_is_its_values() -> None:
    assert as_cell(np.array([1, 2]).data, "start", (5, 5)) == (1, 2)


def test_a_two_d_memoryview_sequence_gives_the_rows_of_its_array() -> None:
    rows = as_sequence(MEMORYVIEW_2D, "items")
    assert len(rows) == 2
    assert all(np.array_equal(row, [0.0, 0.0]) for row in rows)
    assert [r.tolist() for r in unpack(np.arange(6.0).reshape(3, 2).data, "x")] == [
        [0.0, 1.0],
        [2.0, 3.0],
        [4.0, 5.0],
    ]


def test_unpack_of_a_plain_iterable_is_its_tuple() -> None:
    assert unpack(iter([1, 2]), "x") == (1, 2)
    with pytest.raises(TypeError):
        unpack(3, "x")


@pytest.mark.parametrize(
    "view",
    [
        pytest.param(lambda a: np.broadcast_to(a[:1], a.shape), id="broadcast"),
        pytest.param(lambda a: a[::-1].copy()[::-1], id="reversed"),
    ],
)
def test_one_d_views_with_non_positive_strides_come_back_contiguous(view: object) -> None:
    values = np.array([3.0, 3.0, 3.0])
    arr = as_float_array(view(values), "v")  # type: ignore[operator]
    assert arr.flags.c_contiguous
    assert np.array_equal(arr, values)


def test_a_two_d_memoryview_clamp_is_refused_as_no_pair_of_numbers() -> None:
    grid = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.1)
    scan = LaserScan([0.3, 0.3], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0)
    with pytest.raises(TypeError, match=r"^clamp\[0\] must be a real number"):
        integrate_scan(grid, scan, (0.5, 0.5, 0.0), clamp=np.zeros((2, 1)).data)  # type: ignore[arg-type]
