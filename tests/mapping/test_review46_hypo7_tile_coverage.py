"""Metamorphic properties of read_map's tile-coverage check (review 46, HYPO7).

``_boxes_cover`` (a sweep across x over y bands, halving its events) is
compared with a pixel mask by FILES' test on boxes up to 14 pixels. Here:
larger boxes and images (up to 60 pixels, many boxes, so the halving runs
deep even at the default table size), degenerate boxes (zero width or
height, inverted, wholly outside), and the properties any union has: the
answer is the same for any order of the boxes, for boxes repeated, with
empty boxes added, and with the image and boxes transposed or mirrored;
adding a box never uncovers the image, and a covering set stays covering
with any box that lies inside another taken out.
"""

from __future__ import annotations

from itertools import pairwise

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import navkit.mapping.io._map_files as map_files

_Box = tuple[int, int, int, int]


def _pixels(boxes: list[_Box], width: int, height: int) -> bool:
    mask = np.zeros((height, width), dtype=bool)
    for x0, y0, x1, y1 in boxes:
        mask[max(y0, 0) : max(y1, 0), max(x0, 0) : max(x1, 0)] = True
    return bool(mask.all())


def _cover(boxes: list[_Box], width: int, height: int, dense: int = 1 << 15) -> bool:
    array = np.array(boxes, dtype=np.int64).reshape(-1, 4)
    return map_files._boxes_cover(array, width, height, dense)


@st.composite
def _cases(draw: st.DrawFn) -> tuple[list[_Box], int, int]:
    """Boxes over an image: a random tiling (some tiles cut or dropped) plus random boxes."""
    width, height = draw(st.integers(1, 60)), draw(st.integers(1, 60))
    coord = st.integers(-5, 65)
    xs = sorted({0, width, *draw(st.lists(st.integers(1, width), max_size=8))})
    ys = sorted({0, height, *draw(st.lists(st.integers(1, height), max_size=8))})
    boxes = [(a, c, b, d) for a, b in pairwise(xs) for c, d in pairwise(ys)]
    for _ in range(draw(st.integers(0, 3))):
        if not boxes:
            break
        x0, y0, x1, y1 = boxes.pop(draw(st.integers(0, len(boxes) - 1)))
        cut = draw(st.integers(0, 4))  # 4: dropped; else one side moved in by 1
        if cut < 4:
            boxes.append((x0 + (cut == 0), y0 + (cut == 1), x1 - (cut == 2), y1 - (cut == 3)))
    boxes += draw(st.lists(st.tuples(coord, coord, coord, coord), max_size=10))
    # Degenerate boxes: zero width or height at random places, and inverted ones.
    for _ in range(draw(st.integers(0, 3))):
        x, y, size = draw(coord), draw(coord), draw(st.integers(0, 70))
        boxes.append(
            draw(
                st.sampled_from(
                    [(x, y, x, y + size), (x, y, x + size, y), (x + size, y + size, x, y)]
                )
            )
        )
    return draw(st.permutations(boxes)), width, height


_DENSE = st.sampled_from([1, 3, 17, 1 << 15])


@settings(max_examples=120, deadline=None)
@given(case=_cases(), dense=_DENSE)
def test_the_sweep_is_a_pixel_union(case: tuple[list[_Box], int, int], dense: int) -> None:
    boxes, width, height = case
    assert _cover(boxes, width, height, dense) == _pixels(boxes, width, height)


@settings(max_examples=100, deadline=None)
@given(case=_cases(), dense=_DENSE, data=st.data())
def test_order_repeats_and_empty_boxes_change_nothing(
    case: tuple[list[_Box], int, int], dense: int, data: st.DataObject
) -> None:
    boxes, width, height = case
    answer = _cover(boxes, width, height, dense)
    shuffled = data.draw(st.permutations(boxes))
    assert _cover(shuffled, width, height, dense) == answer
    if boxes:
        repeats = data.draw(st.lists(st.sampled_from(boxes), max_size=8))
        assert _cover(boxes + repeats, width, height, dense) == answer
    empty = [
        (5, 5, 5, 9),
        (3, 7, 9, 7),
        (9, 9, 2, 2),
        (-9, -9, -1, -1),
        (width, 0, width + 9, height),
    ]
    assert (
        _cover(
            boxes + data.draw(st.lists(st.sampled_from(empty), max_size=5)), width, height, dense
        )
        == answer
    )


def _transpose(boxes: list[_Box]) -> list[_Box]:
    return [(y0, x0, y1, x1) for x0, y0, x1, y1 in boxes]


def _mirror_x(boxes: list[_Box], width: int) -> list[_Box]:
    # A box's pixels [x0, x1) go to [width - x1, width - x0): inverted boxes stay inverted.
    return [(width - x1, y0, width - x0, y1) for x0, y0, x1, y1 in boxes]


@settings(max_examples=100, deadline=None)
@given(case=_cases(), dense=_DENSE)
def test_transposed_and_mirrored_images_are_covered_alike(
    case: tuple[list[_Box], int, int], dense: int
) -> None:
    boxes, width, height = case
    answer = _cover(boxes, width, height, dense)
    assert _cover(_transpose(boxes), height, width, dense) == answer
    assert _cover(_mirror_x(boxes, width), width, height, dense) == answer
    flipped = _transpose(_mirror_x(_transpose(boxes), height))  # mirrored in y
    assert _cover(flipped, width, height, dense) == answer


@settings(max_examples=100, deadline=None)
@given(case=_cases(), dense=_DENSE, data=st.data())
def test_a_box_added_never_uncovers_and_one_inside_another_is_not_needed(
    case: tuple[list[_Box], int, int], dense: int, data: st.DataObject
) -> None:
    boxes, width, height = case
    answer = _cover(boxes, width, height, dense)
    coord = st.integers(-5, 65)
    extra = data.draw(st.tuples(coord, coord, coord, coord))
    if answer:
        assert _cover([*boxes, extra], width, height, dense)
    # A part of a box, added, changes nothing: it covers no pixel the box does not.
    real = [b for b in boxes if b[2] > b[0] and b[3] > b[1]]
    if real:
        x0, y0, x1, y1 = data.draw(st.sampled_from(real))
        a, b = sorted(data.draw(st.tuples(st.integers(x0, x1), st.integers(x0, x1))))
        c, d = sorted(data.draw(st.tuples(st.integers(y0, y1), st.integers(y0, y1))))
        assert _cover([*boxes, (a, c, b, d)], width, height, dense) == answer
    # The whole image as one box covers it whatever else there is.
    assert _cover([*boxes, (0, 0, width, height)], width, height, dense)
