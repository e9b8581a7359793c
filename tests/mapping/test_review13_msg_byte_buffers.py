"""Message data forwarded as a buffer: memoryviews read as int8 cells (review 13).

rclpy's ``OccupancyGrid.data`` is an ``array.array('b')``; a node forwarding it
may pass ``bytes(msg.data)``, a ``bytearray`` or a ``memoryview`` of either (or
of the array). NumPy reads a memoryview of ``bytes`` or of a ``bytearray``
(format ``'B'``) as uint8, so unknown cells (``0xFF``) read as 255 and the map
was refused. Every such form now reads as the array does: ``0xFF`` is -1.
"""

from __future__ import annotations

import array
from collections.abc import Callable
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import ros_fakes as ros
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import OccupancyGridMsgFields, grid_from_msg, grid_to_msg_fields

# Every value a message holds, unknown (-1, 0xFF) first.
VALUES = [-1, *range(101)]


def _msg(data: Any, width: int, height: int = 1) -> Any:
    msg = ros.OccupancyGrid()
    msg.info.width = width
    msg.info.height = height
    msg.info.resolution = 0.05
    msg.info.origin.position.x = 1.5
    msg.info.origin.orientation.z = 0.6
    msg.info.origin.orientation.w = 0.8
    # rclpy's setter takes an array.array('b') only: a node forwarding the buffer
    # passes a look-alike holding the received info and the buffer.
    return SimpleNamespace(info=ros.deliver(msg).info, data=data)


# The forms a forwarded buffer takes, made from rclpy's array.array('b').
FORMS: dict[str, Callable[[array.array[int]], Any]] = {
    "bytes": lambda a: a.tobytes(),
    "bytearray": lambda a: bytearray(a.tobytes()),
    "memoryview(bytes)": lambda a: memoryview(a.tobytes()),
    "memoryview(bytearray)": lambda a: memoryview(bytearray(a.tobytes())),
    "memoryview(array('b'))": lambda a: memoryview(a),
    "memoryview(array('B'))": lambda a: memoryview(array.array("B", a.tobytes())),
    "memoryview cast to 'c'": lambda a: memoryview(a.tobytes()).cast("c"),
    "memoryview cast to 'B'": lambda a: memoryview(a).cast("B"),
    "memoryview of a uint8 ndarray": lambda a: memoryview(np.frombuffer(a, np.uint8).copy()),
}


def _same_grid(a: OccupancyGrid, b: OccupancyGrid) -> None:
    np.testing.assert_array_equal(a.logodds, b.logodds)
    assert a.shape == b.shape and a.resolution == b.resolution and a.origin == b.origin


@pytest.mark.parametrize("form", FORMS)
def test_each_form_reads_as_the_array(form: str) -> None:
    cells = array.array("b", VALUES + VALUES[::-1])
    expected = grid_from_msg(_msg(cells, 17, 12))
    assert expected.unknown()[0, 0]  # -1 is unknown, not refused or occupied
    data = FORMS[form](cells)
    _same_grid(grid_from_msg(_msg(data, 17, 12)), expected)
    fields = OccupancyGridMsgFields(17, 12, 0.05, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), data)
    assert fields.data.tolist() == cells.tolist()


@pytest.mark.parametrize("form", FORMS)
def test_the_forwarded_buffer_is_neither_modified_nor_shared(form: str) -> None:
    cells = array.array("b", VALUES)
    data = FORMS[form](cells)
    before = bytes(data)
    grid = grid_from_msg(_msg(data, 102))
    fields = OccupancyGridMsgFields(102, 1, 0.05, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), data)
    assert bytes(data) == before
    if isinstance(data, memoryview) and not data.readonly:
        # A writable buffer changed afterwards changes neither result.
        data.cast("B")[:] = bytes(len(before))
        assert grid.unknown()[0, 0] and fields.data[0] == -1


def test_a_received_map_forwarded_as_memoryview_comes_back_unchanged() -> None:
    # The journey: /map in as rclpy's array, forwarded as a memoryview, published again.
    rng = np.random.default_rng(13)
    cells = array.array("b", rng.choice(VALUES, 40 * 30).tolist())
    grid = grid_from_msg(_msg(memoryview(cells.tobytes()), 40, 30))
    published = grid_to_msg_fields(grid).data
    expected = np.array(cells, dtype=np.int8)
    expected[expected == 50] = -1  # 50 is p = 0.5, published as never observed
    np.testing.assert_array_equal(published, expected)


def test_a_two_dimensional_memoryview_reads_as_the_int8_array_of_that_shape() -> None:
    cells = array.array("b", VALUES[:100])
    view = memoryview(cells.tobytes()).cast("B", shape=[10, 10])
    as_array = np.frombuffer(cells, np.int8).reshape(10, 10)
    _same_grid(grid_from_msg(_msg(view, 10, 10)), grid_from_msg(_msg(as_array, 10, 10)))
    with pytest.raises(ValueError, match=r"data must have shape \(100,\)"):
        OccupancyGridMsgFields(10, 10, 0.05, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), view)


def test_a_strided_memoryview_reads_its_own_cells() -> None:
    cells = np.array(VALUES, dtype=np.int8)
    view = memoryview(cells.view(np.uint8))[::2]
    grid = grid_from_msg(_msg(view, 51))
    _same_grid(grid, grid_from_msg(_msg(array.array("b", cells[::2].tolist()), 51)))


def test_a_memoryview_of_wider_integers_holds_values_not_bytes() -> None:
    # int16 values -1..100 are values: 0xFFFF is -1 as a value, not two cells.
    cells = array.array("h", VALUES)
    grid = grid_from_msg(_msg(memoryview(cells), 102))
    _same_grid(grid, grid_from_msg(_msg(array.array("b", VALUES), 102)))


@pytest.mark.parametrize("byte", [0x80, 0xFE, 0x65])
def test_bytes_outside_the_range_are_refused_in_every_form(byte: int) -> None:
    # 0x80 is -128, 0xFE -2, 0x65 is 101: no occupancy value.
    cells = array.array("b", bytes([0, byte, 100]))
    for make in FORMS.values():
        with pytest.raises(
            ValueError, match=r"msg\.data values must be -1 \(unknown\) or 0\.\.100"
        ):
            grid_from_msg(_msg(make(cells), 3))


def test_a_released_memoryview_is_refused_by_name() -> None:
    view = memoryview(b"\x00\x01")
    view.release()
    with pytest.raises(ValueError, match=r"msg\.data is a released memoryview"):
        grid_from_msg(_msg(view, 2))
    with pytest.raises(ValueError, match=r"^data is a released memoryview"):
        OccupancyGridMsgFields(2, 1, 0.05, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), view)


@pytest.mark.parametrize(
    ("view", "dtype"),
    [
        (memoryview(array.array("d", [0.0, 1.0])), "float64"),
        (memoryview(array.array("f", [0.0, 1.0])), "float32"),
        (memoryview(np.array([True, False])), "bool"),
    ],
)
def test_memoryviews_of_other_types_are_refused_as_before(view: memoryview, dtype: str) -> None:
    with pytest.raises(TypeError, match=rf"msg\.data must hold integers, got dtype {dtype}"):
        grid_from_msg(_msg(view, 2))


def test_a_uint8_array_holding_255_says_what_to_pass() -> None:
    # A NumPy uint8 array is read as its values (an image's, say): 255 is not
    # taken for -1 behind the user's back, but the message says how to mean it.
    cells = np.array(VALUES, dtype=np.int8)
    raw = cells.view(np.uint8)
    with pytest.raises(ValueError, match=r"pass msg\.data\.view\(np\.int8\) or its bytes"):
        grid_from_msg(_msg(raw, 102))
    expected = grid_from_msg(_msg(array.array("b", VALUES), 102))
    _same_grid(grid_from_msg(_msg(raw.view(np.int8), 102)), expected)
    _same_grid(grid_from_msg(_msg(raw.tobytes(), 102)), expected)
    with pytest.raises(ValueError, match=r"pass data\.view\(np\.int8\)"):
        OccupancyGridMsgFields(102, 1, 0.05, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), raw)
    # Other out-of-range uint8 values get no such hint: they are no int8 cells' bytes.
    with pytest.raises(ValueError, match=r"or 0\.\.100$"):
        grid_from_msg(_msg(np.array([101, 0], dtype=np.uint8), 2))


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.sampled_from(VALUES), min_size=1, max_size=60),
    st.sampled_from(sorted(FORMS)),
)
def test_any_map_reads_the_same_in_every_form(values: list[int], form: str) -> None:
    cells = array.array("b", values)
    expected = grid_from_msg(_msg(cells, len(values)))
    _same_grid(grid_from_msg(_msg(FORMS[form](cells), len(values))), expected)
