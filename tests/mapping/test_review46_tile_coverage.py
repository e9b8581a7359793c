"""The tile-coverage check of ``read_map`` is exact for any tiles (review 46).

Review 45 refused an image whose Pillow tiles do not cover its declared size
by the union of the tile boxes on the grid of their edges, but past a grid of
``max(65536, 4 x tiles)`` cells it compared total areas only: a crafted file of
overlapping tiles leaving a gap passed, and Pillow filled the gap with zeros
(white in a TIFF whose 0 is white: invented free space). ``_boxes_cover`` now
sweeps across x with the counts of y bands, halving the events (O(T log T) for
T tiles, memory O(T)): exact at any size. Strips, regular tiles and real maps
read as before.
"""

from __future__ import annotations

import io
from itertools import pairwise
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st
from PIL import Image, ImageFile

import navkit.mapping.io._map_files as map_files
from navkit.mapping.io import read_map

_N = 300  # 301 x 301 edges: beyond review 45's 65536-cell grid
_PIXELS = (np.arange(_N * _N) % 251).astype(np.uint8).reshape(_N, _N)


def _tiff(pixels: np.ndarray, **save: Any) -> bytes:
    out = io.BytesIO()
    Image.fromarray(pixels).save(out, format="TIFF", **save)
    return out.getvalue()


def _crafted_tiles(offset: int, gap: int | None, n: int = _N) -> list[ImageFile._Tile]:
    """Raw tiles of the one-strip TIFF of an ``n`` x ``n`` image whose data starts at ``offset``.

    A tile a column (all but column ``gap``), and a tile a row over the half of
    the image without ``gap``: the tiles overlap, their area exceeds the
    image's, and ``gap`` is covered by none of them.
    """
    columns = [
        ImageFile._Tile("raw", (i, 0, i + 1, n), offset + i, ("L", n, 1))
        for i in range(n)
        if i != gap
    ]
    left, right = (0, n // 2) if gap is None or gap >= n // 2 else (n // 2, n)
    rows = [
        ImageFile._Tile("raw", (left, k, right, k + 1), offset + k * n + left, ("L", 0, 1))
        for k in range(n)
    ]
    return columns + rows


def _old_grid_fallback(size: tuple[int, int], boxes: np.ndarray) -> bool:
    """Whether review 45's check would have compared areas only (and found them enough)."""
    width, height = size
    xs = np.unique(np.concatenate([boxes[:, 0::2].ravel(), [0, width]]))
    ys = np.unique(np.concatenate([boxes[:, 1::2].ravel(), [0, height]]))
    area = int(((boxes[:, 2] - boxes[:, 0]) * (boxes[:, 3] - boxes[:, 1])).sum())
    return len(xs) * len(ys) > max(1 << 16, 4 * len(boxes)) and area >= width * height


def _map(folder: Path, image: bytes) -> Path:
    (folder / "m.tiff").write_bytes(image)
    yaml_path = folder / "m.yaml"
    yaml_path.write_text(
        "image: m.tiff\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: scale\n"
    )
    return yaml_path


def _opens_with_tiles(monkeypatch: pytest.MonkeyPatch, gap: int | None, n: int = _N) -> None:
    """Pillow's ``open``, the image's one strip replaced by :func:`_crafted_tiles`."""
    real_open = Image.open

    def open_crafted(fp: Any, *args: Any, **kwargs: Any) -> Any:
        img = real_open(fp, *args, **kwargs)
        img.tile = _crafted_tiles(img.tile[0].offset, gap, n)
        return img

    monkeypatch.setattr(Image, "open", open_crafted)


@pytest.mark.parametrize("gap", [0, 7, _N // 2, _N - 1])
def test_overlapping_tiles_with_a_gap_are_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, gap: int
) -> None:
    image = _tiff(_PIXELS)
    with Image.open(io.BytesIO(image)) as img:
        tiles = _crafted_tiles(img.tile[0].offset, gap)
        boxes = np.array([tile.extents for tile in tiles], dtype=np.int64)
        assert _old_grid_fallback(img.size, boxes)  # the premise: areas alone passed
        img.tile = tiles
        with pytest.raises(ValueError) as direct:
            map_files._check_tiles(img, tmp_path / "m.tiff")
    assert str(direct.value) == (
        f"{tmp_path / 'm.tiff'}: the image data does not cover its declared size of "
        f"{_N} x {_N} pixels (width x height; is its header corrupted?)"
    )
    yaml_path = _map(tmp_path, image)
    _opens_with_tiles(monkeypatch, gap)
    with pytest.raises(ValueError) as raised:
        read_map(yaml_path)
    # The words of every other uncovered image (test_review45_image_tiles).
    assert str(raised.value) == f"{yaml_path}: map image {direct.value}"


def test_overlapping_tiles_without_a_gap_pass(tmp_path: Path) -> None:
    with Image.open(io.BytesIO(_tiff(_PIXELS))) as img:
        img.tile = _crafted_tiles(img.tile[0].offset, None)
        boxes = np.array([tile.extents for tile in img.tile], dtype=np.int64)
        assert _old_grid_fallback(img.size, boxes)
        map_files._check_tiles(img, tmp_path / "m.tiff")


def test_overlapping_tiles_without_a_gap_read_the_image(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Small: Pillow decodes a tile of one column a byte at a time (26 million
    # decoder calls, a minute, for the 300 x 300 image).
    pixels = _PIXELS[:40, :40].copy()
    image = _tiff(pixels)
    plain = read_map(_map(tmp_path, image))
    _opens_with_tiles(monkeypatch, None, 40)
    crafted = read_map(_map(tmp_path, image))
    np.testing.assert_array_equal(crafted.logodds, plain.logodds)
    assert len(np.unique(plain.logodds)) > 50  # the pixels, not one colour


def _covers(boxes: np.ndarray, width: int, height: int) -> bool:
    """Whether ``_check_tiles`` lets a TIFF of ``boxes`` through."""
    img = SimpleNamespace(format="TIFF", size=(width, height), tile=[("raw", b) for b in boxes])
    try:
        map_files._check_tiles(img, Path("m.tiff"))
    except ValueError as exc:
        assert str(exc).startswith("m.tiff: the image data does not cover its declared size")
        return False
    return True


def test_a_one_pixel_hole_among_many_overlapping_tiles_is_found() -> None:
    # 2000 tiles with distinct edges (a 4 million-cell grid of edges), one pixel uncovered.
    rng = np.random.default_rng(46)
    size = 5000
    boxes = np.sort(rng.integers(0, size + 1, (2000, 2, 2)), axis=2)
    boxes = boxes[:, [0, 1, 0, 1], [0, 0, 1, 1]]  # (x0, y0, x1, y1)
    hole = (1234, 4321)
    x, y = hole
    around = [(0, 0, x, size), (x + 1, 0, size, size), (0, 0, size, y), (0, y + 1, size, size)]
    boxes = np.concatenate([boxes, np.array(around, np.int64)])
    inside = (boxes[:, 0] <= x) & (x < boxes[:, 2]) & (boxes[:, 1] <= y) & (y < boxes[:, 3])
    assert not _covers(boxes[~inside], size, size)
    assert _covers(boxes, size, size) == bool(inside.any())
    assert _covers(np.concatenate([boxes, [[x, y, x + 1, y + 1]]]), size, size)


@pytest.mark.parametrize("count", [2, 7, 300])
def test_strips_and_tiles_are_covered_and_one_missing_is_not(count: int) -> None:
    strips = np.array([(0, k, 40, k + 1) for k in range(count)], np.int64)
    assert _covers(strips, 40, count)
    assert not _covers(strips[:-1], 40, count)
    corners = [(16 * c, 16 * r) for r in range(count) for c in range(5)]
    tiles = np.array([(x, y, x + 16, y + 16) for x, y in corners], np.int64)
    assert _covers(tiles, 75, 16 * count - 3)  # tiles beyond the edges
    for missing in (0, len(tiles) // 2, len(tiles) - 1):
        assert not _covers(np.delete(tiles, missing, axis=0), 75, 16 * count - 3)


def _covered_by_pixels(boxes: list[tuple[int, int, int, int]], width: int, height: int) -> bool:
    mask = np.zeros((height, width), dtype=bool)
    for x0, y0, x1, y1 in boxes:
        mask[max(y0, 0) : max(y1, 0), max(x0, 0) : max(x1, 0)] = True
    return bool(mask.all())


_COORD = st.integers(-3, 14)
_BOX = st.tuples(_COORD, _COORD, _COORD, _COORD)


@st.composite
def _tilings(draw: st.DrawFn) -> tuple[list[tuple[int, int, int, int]], int, int]:
    """A grid of tiles over the image, some dropped or shrunk, some overlapping extras."""
    width, height = draw(st.integers(1, 12)), draw(st.integers(1, 12))
    xs = sorted({0, width, *draw(st.lists(st.integers(1, width), max_size=4))})
    ys = sorted({0, height, *draw(st.lists(st.integers(1, height), max_size=4))})
    boxes = [(a, c, b, d) for a, b in pairwise(xs) for c, d in pairwise(ys)]
    for _ in range(draw(st.integers(0, min(2, len(boxes))))):
        index = draw(st.integers(0, len(boxes) - 1))
        x0, y0, x1, y1 = boxes.pop(index)
        if draw(st.booleans()):  # shrunk by one pixel on one side, else dropped
            side = draw(st.integers(0, 3))
            boxes.append((x0 + (side == 0), y0 + (side == 1), x1 - (side == 2), y1 - (side == 3)))
    boxes += draw(st.lists(_BOX, max_size=6))
    return draw(st.permutations(boxes)), width, height


@settings(max_examples=300, deadline=None)
@given(
    case=st.one_of(
        _tilings(),
        st.tuples(st.lists(_BOX, max_size=12), st.integers(0, 12), st.integers(0, 12)),
    ),
    dense=st.sampled_from([1, 2, 5, 40, 1 << 15]),  # 1 << 15: the default
)
def test_the_sweep_agrees_with_a_pixel_mask(
    case: tuple[list[tuple[int, int, int, int]], int, int], dense: int
) -> None:
    boxes, width, height = case
    expected = _covered_by_pixels(boxes, width, height)
    array = np.array(boxes, dtype=np.int64).reshape(-1, 4)
    before = array.copy()
    assert map_files._boxes_cover(array, width, height, dense) == expected
    np.testing.assert_array_equal(array, before)  # the boxes are not clipped in place
    img = SimpleNamespace(format="TIFF", size=(width, height), tile=[("raw", box) for box in boxes])
    if not boxes:
        return  # no tiles: decoded by the plugin's own load, not checked
    if expected:
        map_files._check_tiles(img, Path("m.tiff"))
    else:
        with pytest.raises(ValueError, match=r"^m\.tiff: the image data does not cover"):
            map_files._check_tiles(img, Path("m.tiff"))


def _real_maps(shared_data: Path) -> list[Path]:
    maps = sorted((shared_data / "ros-map-server-maps").glob("*/*.yaml"))
    if not maps:
        pytest.skip("no ros-map-server-maps in the shared data")
    return maps


@pytest.mark.parametrize(
    "save",
    [
        pytest.param({"format": "TIFF"}, id="tiff"),
        pytest.param({"format": "TIFF", "tiffinfo": {278: 1}}, id="tiff-a-strip-a-row"),
        pytest.param({"format": "TIFF", "tiffinfo": {278: 7}}, id="tiff-strips-of-7-rows"),
        pytest.param({"format": "TIFF", "compression": "tiff_lzw"}, id="tiff-lzw"),
        pytest.param({"format": "PNG"}, id="png"),
        pytest.param({"format": "PPM"}, id="pgm-by-pillow"),
    ],
)
def test_real_maps_read_the_same_in_other_formats(
    shared_data: Path, tmp_path: Path, save: dict[str, Any]
) -> None:
    for yaml_path in _real_maps(shared_data):
        original = read_map(yaml_path)
        image = yaml_path.parent / yaml.safe_load(yaml_path.read_text())["image"]
        copy = tmp_path / yaml_path.parent.name
        copy.mkdir()
        suffix = {"TIFF": ".tiff", "PNG": ".png", "PPM": ".pgm"}[save["format"]]
        with Image.open(image) as img:
            img.save(copy / f"m{suffix}", **save)
        text = yaml_path.read_text().replace(image.name, f"m{suffix}")
        (copy / "m.yaml").write_text(text)
        converted = read_map(copy / "m.yaml")
        np.testing.assert_array_equal(converted.logodds, original.logodds)
        assert converted.resolution == original.resolution


def test_real_maps_read_the_same_as_tiled_tiffs(shared_data: Path, tmp_path: Path) -> None:
    tifffile = pytest.importorskip("tifffile")
    for yaml_path in _real_maps(shared_data):
        original = read_map(yaml_path)
        image = yaml_path.parent / yaml.safe_load(yaml_path.read_text())["image"]
        copy = tmp_path / yaml_path.parent.name
        copy.mkdir()
        with Image.open(image) as img:
            pixels = np.asarray(img)
        tifffile.imwrite(copy / "m.tiff", pixels, tile=(16, 16))
        with Image.open(copy / "m.tiff") as img:  # the premise: Pillow reads it in tiles
            assert len(img.tile) == -(-pixels.shape[0] // 16) * -(-pixels.shape[1] // 16)
        (copy / "m.yaml").write_text(yaml_path.read_text().replace(image.name, "m.tiff"))
        np.testing.assert_array_equal(read_map(copy / "m.yaml").logodds, original.logodds)
