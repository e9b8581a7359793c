"""``OccupancyGrid.world_to_cell``: the (N, 2) float64 fast path equals the general path.

The fast path takes exact, C-contiguous float64 ndarrays (aligned or not) of shape
(N, 2) straight to the compiled kernel and allocates the cells with the
points' own shape tuple; everything else (lists, other dtypes, strided or
Fortran arrays, subclasses, single points) goes through the general path. Both
must give the same cells bit for bit, a fresh writeable int64 array that shares
nothing with the input, and the same errors.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid


class _Sub(np.ndarray):
    """An ndarray subclass: never the fast path."""


def _grid(yaw: float = 0.4) -> OccupancyGrid:
    return OccupancyGrid.empty(
        width=5.0, height=4.0, resolution=0.05, origin=Pose2D(-2.0, -1.5, yaw)
    )


def _general(grid: OccupancyGrid, pts: np.ndarray) -> np.ndarray:
    """The general path: the same points as nested lists."""
    out: np.ndarray = grid.world_to_cell(pts.tolist())
    return out


def _variants(pts: np.ndarray) -> list[tuple[str, Any]]:
    ro = pts.copy()
    ro.flags.writeable = False
    wide = np.zeros((pts.shape[0], 4))
    wide[:, ::2] = pts
    twice = np.repeat(pts, 2, axis=0)
    return [
        ("exact", pts.copy()),
        ("list", pts.tolist()),
        ("tuple rows", [tuple(p) for p in pts.tolist()]),
        ("read-only", ro),
        ("fortran", np.asfortranarray(pts)),
        ("strided columns", wide[:, ::2]),
        ("strided rows", twice[::2]),
        ("subclass", pts.copy().view(_Sub)),
        ("big-endian", pts.astype(">f8")),
        ("longdouble", pts.astype(np.longdouble)),
    ]


@settings(max_examples=40, deadline=None)
@given(
    n=st.integers(0, 12),
    seed=st.integers(0, 2**32 - 1),
    yaw=st.floats(-3.14, 3.14),
    scale=st.sampled_from([1e-3, 1.0, 10.0, 1e6, 1e20]),
)
def test_every_input_form_gives_the_general_paths_cells(
    n: int, seed: int, yaw: float, scale: float
) -> None:
    grid = _grid(yaw)
    pts = np.random.default_rng(seed).uniform(-scale, scale, size=(n, 2))
    want = _general(grid, pts) if n else grid.world_to_cell(np.empty((0, 2)).tolist())
    for label, points in _variants(pts):
        before = np.array(points, dtype=np.float64, copy=True)
        got = grid.world_to_cell(points)
        assert got.dtype == np.int64 and got.shape == (n, 2), label
        assert got.tobytes() == np.asarray(want, dtype=np.int64).reshape(n, 2).tobytes(), label
        assert got.flags.writeable and got.flags.c_contiguous and got.flags.owndata, label
        if isinstance(points, np.ndarray):
            assert not np.shares_memory(got, points), label
        np.testing.assert_array_equal(np.array(points, dtype=np.float64), before)


def test_float32_and_integer_points_are_converted_like_lists() -> None:
    grid = _grid()
    pts = np.array([[0.3, 0.7], [-1.25, 2.0], [1.0, -1.0]])
    for dtype in (np.float32, np.float16, np.int64, np.int8):
        cast = pts.astype(dtype)
        np.testing.assert_array_equal(grid.world_to_cell(cast), _general(grid, cast))


def test_single_row_with_odd_strides_and_single_points() -> None:
    grid = _grid()
    base = np.arange(20.0).reshape(10, 2) / 7.0
    one_row = base[3:4]  # shape (1, 2), C-contiguous
    odd = np.lib.stride_tricks.as_strided(base, shape=(1, 2), strides=(160, 8))
    want = _general(grid, base[3:4])
    np.testing.assert_array_equal(grid.world_to_cell(one_row), want)
    np.testing.assert_array_equal(grid.world_to_cell(odd), _general(grid, odd))
    point = grid.world_to_cell(base[3])
    assert point.shape == (2,)
    np.testing.assert_array_equal(point, want[0])


def test_fresh_cells_each_call_with_their_own_shape() -> None:
    grid = _grid()
    pts = np.array([[0.1, 0.2], [0.3, 0.4]])
    shape = pts.shape
    a = grid.world_to_cell(pts)
    b = grid.world_to_cell(pts)
    assert a is not b and not np.shares_memory(a, b)
    a[:] = -7
    np.testing.assert_array_equal(b, grid.world_to_cell(pts))
    assert pts.shape == shape and pts.dtype == np.float64


def _error(call: Callable[[], Any]) -> tuple[type[BaseException], str]:
    with pytest.raises((TypeError, ValueError)) as info:
        call()
    return type(info.value), str(info.value)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
@pytest.mark.parametrize("row", [0, 4])
def test_non_finite_points_get_the_general_paths_error(bad: float, row: int) -> None:
    grid = _grid()
    pts = np.random.default_rng(row).uniform(-3, 3, size=(5, 2))
    pts[row, 1] = bad
    fast = _error(lambda: grid.world_to_cell(pts))
    assert fast == _error(lambda: grid.world_to_cell(pts.tolist()))
    assert fast == _error(lambda: grid.world_to_cell(np.asfortranarray(pts)))
    assert "points_xy" in fast[1]


@pytest.mark.parametrize(
    "points",
    [
        np.zeros((3, 3)),
        np.zeros((2, 2, 2)),
        np.zeros(3),
        np.array([[True, False]]),
        np.array([[1 + 0j, 2.0]]),
        np.array([["a", "b"]]),
        [[0.0, 1.0], [2.0]],
        "0.0, 1.0",
        None,
    ],
)
def test_malformed_points_refused_naming_the_argument(points: Any) -> None:
    grid = _grid()
    kind, message = _error(lambda: grid.world_to_cell(points))
    assert "points_xy" in message
    assert kind in (TypeError, ValueError)


def test_continuous_flag_still_validated_and_general() -> None:
    grid = _grid()
    pts = np.array([[0.1, 0.2], [0.3, 0.4]])
    for bad in (1, 0, 0.0, "no", None):
        with pytest.raises(TypeError, match="continuous"):
            grid.world_to_cell(pts, continuous=bad)  # type: ignore[call-overload]
    # NumPy bools are bools (the general path), with the plain False's cells.
    np.testing.assert_array_equal(
        grid.world_to_cell(pts, continuous=np.bool_(False)),  # type: ignore[call-overload]
        grid.world_to_cell(pts),
    )
    np.testing.assert_array_equal(
        grid.world_to_cell(pts, continuous=True), grid.world_to_cell(pts.tolist(), continuous=True)
    )
