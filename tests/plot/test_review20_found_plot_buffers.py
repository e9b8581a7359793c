"""plot_path and the animation footprint take the array-likes the rest of navkit takes.

Review 20, FOUND item 2: ``plot_path(memoryview(points))`` was refused ("path
must be a Path2D or an (n, 2) array, got memoryview") while ``navkit.sim``
takes the same memoryview as a reference path. The plot package now accepts
memoryviews, ``array.array`` and objects NumPy reads through its array
protocols (``__array__``, ``__array_interface__``), drawing exactly what the
plain array draws; non-arrays keep their clear TypeError.
"""

from __future__ import annotations

import array
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from navkit.plot import plot_path
from navkit.plot._animate import _footprint

pytest.importorskip("matplotlib")


class ArrayOnly:
    """A foreign array type NumPy reads only through ``__array__``."""

    def __init__(self, data: np.ndarray) -> None:
        self._data = data

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        return np.array(self._data, dtype=dtype)


class InterfaceOnly:
    """A buffer NumPy reads only through ``__array_interface__``."""

    def __init__(self, data: np.ndarray) -> None:
        self._data = np.ascontiguousarray(data)
        self.__array_interface__ = self._data.__array_interface__


def _spellings(points: np.ndarray) -> list[Any]:
    big = points.astype(">f8")
    return [memoryview(points), memoryview(big), ArrayOnly(points), InterfaceOnly(points)]


def _drawn(path: Any) -> list[list[float]]:
    import matplotlib.pyplot as plt

    ax = plot_path(path)
    try:
        return np.asarray(ax.lines[0].get_xydata()).tolist()
    finally:
        plt.close(ax.figure)


@settings(max_examples=20, deadline=None)
@given(
    hnp.arrays(
        np.float64,
        st.tuples(st.integers(1, 6), st.just(2)),
        elements=st.floats(-1e6, 1e6, allow_nan=False),
    )
)
def test_plot_path_draws_a_foreign_array_as_its_values(points: np.ndarray) -> None:
    want = _drawn(points)
    for spelling in _spellings(points):
        assert _drawn(spelling) == want, type(spelling).__name__
    np.testing.assert_array_equal(np.asarray(memoryview(points)), points)  # unchanged


def test_the_simulation_and_the_plot_take_the_same_memoryview() -> None:
    from navkit.sim._simulation import _reference  # Simulation's reference_path check

    pts = np.array([[0.0, 0.0], [1.0, 0.5], [2.0, 0.5]])
    view = memoryview(pts)
    checked = _reference(view)
    assert checked is not None
    assert _drawn(view) == checked.tolist() == pts.tolist()


def test_plot_path_keeps_refusing_what_is_no_array() -> None:
    for bad in (None, 3.0, "path", b"\x00" * 32, bytearray(32), {"x": 1}, {1, 2}):
        with pytest.raises(TypeError, match="path must be a Path2D or an"):
            plot_path(bad)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="path must have length 2 along axis 1"):
        plot_path(memoryview(np.zeros((3, 3))))
    with pytest.raises(ValueError, match="path must be 2-D"):
        plot_path(array.array("d", [0.0, 1.0]))
    with pytest.raises(TypeError, match="path must hold real numbers"):
        plot_path(memoryview(np.zeros((3, 2), dtype=np.complex128)))


def test_footprint_vertices_as_a_memoryview_are_its_values() -> None:
    square = np.array([[0.2, 0.2], [-0.2, 0.2], [-0.2, -0.2], [0.2, -0.2]])
    want = _footprint(square)
    for spelling in _spellings(square):
        np.testing.assert_array_equal(_footprint(spelling), want)
    with pytest.raises(TypeError, match="footprint must be a radius"):
        _footprint(None)
