"""Map images whose data Pillow would make up or mix (review 45, TILES).

A TIFF whose ``ImageLength`` is corrupted (5 -> 5,898,245) has one strip of
5 rows; Pillow decoded it into the declared size and filled the rest, so
``read_map`` returned a 5,898,245 x 7 grid of invented free space. Pillow's
tiles must now cover the declared image. A 16-bit colour PNG is decoded twice
(high, then low bytes); both decodes now read one in-memory copy of the file,
so a file rewritten between them cannot give a grid mixing two files.
"""

from __future__ import annotations

import io
import struct
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest
from PIL import Image
from test_review45_read_map_adversarial import _png

import navkit.mapping.io._map_files as map_files
from navkit.mapping.io import read_map

_PIXELS = (np.arange(35, dtype=np.uint8).reshape(5, 7) * 7).astype(np.uint8)


def _tiff(pixels: np.ndarray, **save: Any) -> bytes:
    out = io.BytesIO()
    Image.fromarray(pixels).save(out, format="TIFF", **save)
    return out.getvalue()


def _with_height(tiff: bytes, height: int) -> bytes:
    """``tiff`` with its first IFD's ImageLength (tag 257, SHORT or LONG) set to ``height``."""
    data = bytearray(tiff)
    order = {b"II": "<", b"MM": ">"}[bytes(data[:2])]
    ifd = struct.unpack_from(order + "I", data, 4)[0]
    for index in range(struct.unpack_from(order + "H", data, ifd)[0]):
        entry = ifd + 2 + 12 * index
        tag, kind, count = struct.unpack_from(order + "HHI", data, entry)
        if tag == 257:
            assert count == 1
            value = struct.pack(order + ("I" if kind == 4 else "H"), height)
            data[entry + 8 : entry + 8 + len(value)] = value
            return bytes(data)
    raise AssertionError("no ImageLength tag")


def _map(folder: Path, image: bytes, suffix: str) -> Path:
    (folder / f"m{suffix}").write_bytes(image)
    yaml_path = folder / "m.yaml"
    yaml_path.write_text(
        f"image: m{suffix}\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: scale\n"
    )
    return yaml_path


def test_a_tiff_with_a_corrupted_height_is_refused(tmp_path: Path) -> None:
    # 5898245 = 5 + (90 << 16): one flipped byte of a LONG ImageLength of 5.
    broken = _with_height(_tiff(_PIXELS), 5898245)
    with Image.open(io.BytesIO(broken)) as img:  # the premise: one 7 x 5 strip of a 7 x 5898245
        assert img.size == (7, 5898245)
        assert [tuple(tile[1]) for tile in img.tile] == [(0, 0, 7, 5)]
    yaml_path = _map(tmp_path, broken, ".tiff")
    with pytest.raises(ValueError) as raised:
        read_map(yaml_path)
    assert str(raised.value) == (
        f"{yaml_path}: map image {tmp_path / 'm.tiff'}: the image data does not cover its "
        "declared size of 7 x 5898245 pixels (width x height; is its header corrupted?)"
    )
    assert (tmp_path / "m.tiff").read_bytes() == broken


def test_a_tiff_one_row_short_is_refused(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"m\.tiff: the image data does not cover .* 7 x 6 "):
        map_files.read_image(_map_and_image(tmp_path, _with_height(_tiff(_PIXELS), 6)))


def _map_and_image(folder: Path, image: bytes) -> Path:
    _map(folder, image, ".tiff")
    return folder / "m.tiff"


@pytest.mark.parametrize(
    "save",
    [
        pytest.param({"format": "TIFF"}, id="tiff"),
        pytest.param({"format": "TIFF", "tiffinfo": {278: 7}}, id="tiff-strips-of-7-rows"),
        pytest.param({"format": "TIFF", "compression": "tiff_lzw"}, id="tiff-lzw"),
        pytest.param({"format": "GIF"}, id="gif"),
        pytest.param({"format": "PNG"}, id="png"),
        pytest.param({"format": "PPM"}, id="pgm"),
        pytest.param({"format": "BMP"}, id="bmp"),
        pytest.param({"format": "WEBP", "lossless": True}, id="webp-without-tiles"),
    ],
)
def test_whole_images_read_their_pixels(tmp_path: Path, save: dict[str, Any]) -> None:
    pixels = np.random.default_rng(45).integers(0, 256, (50, 31)).astype(np.uint8)
    path = tmp_path / "m.img"
    Image.fromarray(pixels).save(path, **save)
    with Image.open(path) as img:
        strips = len(img.tile)
    if "tiffinfo" in save:
        assert strips == 8  # the premise: 50 rows in strips of 7
    grey, alpha = map_files.read_image(path)
    assert alpha is None
    np.testing.assert_array_equal(grey, pixels.astype(np.float64))


def _fake(size: tuple[int, int], boxes: list[tuple[int, int, int, int]], fmt: str = "TIFF") -> Any:
    return SimpleNamespace(
        format=fmt, size=size, tile=[("raw", box, 0, ("L", 0, 1)) for box in boxes]
    )


_TILES = (0, 0, 3, 3), (3, 0, 6, 3), (0, 3, 3, 6), (3, 3, 6, 6)


@pytest.mark.parametrize(
    ("size", "boxes", "covered"),
    [
        pytest.param((4, 5), [(0, 0, 4, 2), (0, 2, 4, 5)], True, id="strips"),
        pytest.param((4, 5), [(0, 0, 4, 3), (0, 2, 4, 5)], True, id="overlapping-strips"),
        pytest.param((4, 5), [(0, 0, 2, 5), (2, 0, 4, 5)], True, id="columns"),
        pytest.param((6, 6), list(_TILES), True, id="tiles"),
        pytest.param((5, 5), [(0, 0, 8, 8)], True, id="a-tile-beyond-the-edges"),
        pytest.param((4, 5), [(0, 0, 4, 2), (0, 3, 4, 5)], False, id="a-row-missing"),
        pytest.param((4, 5), [(0, 0, 4, 2), (0, 2, 4, 4)], False, id="the-last-row-missing"),
        pytest.param((4, 5), [(0, 0, 4, 2), (0, 2, 3, 5)], False, id="a-column-missing"),
        pytest.param(
            (4, 5), [(0, 0, 4, 2), (0, 0, 4, 2), (0, 2, 4, 4)], False, id="area-but-a-gap"
        ),
        pytest.param((6, 6), list(_TILES[:3]), False, id="a-tile-missing"),
        pytest.param((4, 5), [(0, 0, 4, 5), (3, 1, 1, 3)], True, id="an-inverted-box-too"),
    ],
)
def test_tiles_cover_the_image(
    size: tuple[int, int], boxes: list[tuple[int, int, int, int]], covered: bool
) -> None:
    if covered:
        map_files._check_tiles(_fake(size, boxes), Path("m.tiff"))
    else:
        with pytest.raises(ValueError, match=r"^m\.tiff: the image data does not cover"):
            map_files._check_tiles(_fake(size, boxes), Path("m.tiff"))


def test_gif_frames_may_be_smaller_than_the_canvas() -> None:
    map_files._check_tiles(_fake((10, 10), [(2, 2, 5, 5)], "GIF"), Path("m.gif"))


def _rgb16(seed: int, rows: int = 60, cols: int = 64) -> bytes:
    samples = np.random.default_rng(seed).integers(0, 65536, (rows, cols, 3))
    return _png(samples, 2, 16)


def _opens_rewriting(
    monkeypatch: pytest.MonkeyPatch, path: Path, data: bytes, at: int
) -> list[object]:
    """Pillow's ``open``, the ``at``-th call of which first rewrites ``path`` in place."""
    opened: list[object] = []
    real_open = Image.open

    def open_rewriting(fp: Any, *args: Any, **kwargs: Any) -> Any:
        opened.append(fp)
        if len(opened) == at:
            with open(path, "r+b") as fh:
                fh.write(data)
                fh.truncate()
        return real_open(fp, *args, **kwargs)

    monkeypatch.setattr(Image, "open", open_rewriting)
    return opened


@pytest.mark.parametrize("at", [1, 2, 3])
def test_a_16_bit_png_rewritten_while_read_gives_one_files_grid(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, at: int
) -> None:
    # READCHECK's repro: two random 60 x 64 RGB16 PNGs of the same size and layout;
    # the second written over the first when Pillow opens a file for the at-th time
    # (1: the header; then the two decodes, which read one copy of the file).
    old, new = _rgb16(1), _rgb16(2)
    assert len(old) == len(new)
    grids = {}
    for name, data in (("old", old), ("new", new)):
        (tmp_path / f"{name}.png").write_bytes(data)
        grids[name] = read_map(_map(tmp_path, data, ".png")).logodds
    assert not np.array_equal(grids["old"], grids["new"])
    yaml_path = _map(tmp_path, old, ".png")
    opened = _opens_rewriting(monkeypatch, tmp_path / "m.png", new, at)
    logodds = read_map(yaml_path).logodds
    same = {name: bool(np.array_equal(logodds, grid)) for name, grid in grids.items()}
    assert same == {"old": at > 1, "new": at == 1}, "a grid of neither file"
    assert len(opened) == 3


def test_a_16_bit_png_resized_before_it_is_copied_is_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Rewritten with another size after its header was read and checked.
    yaml_path = _map(tmp_path, _rgb16(1), ".png")
    real = map_files._deep_low_rawmode

    def then_rewritten(img: Any, path: Path) -> str | None:
        low = real(img, path)
        path.write_bytes(_rgb16(2, 64, 60))
        return low

    monkeypatch.setattr(map_files, "_deep_low_rawmode", then_rewritten)
    with pytest.raises(ValueError) as raised:
        read_map(yaml_path)
    assert str(raised.value) == (
        f"{yaml_path}: map image {tmp_path / 'm.png'}: cannot read the image "
        "(ValueError: the file changed while it was read)"
    )


def test_a_16_bit_png_padded_beyond_its_samples_is_refused_unread(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # 2 x 3 RGB16: 2 * (3 * 6 + 1) = 38 bytes of samples; with 100 bytes of slack
    # for the other chunks, files of up to 2 * 38 + 100 = 176 bytes are read.
    monkeypatch.setattr(map_files, "_DEEP_PNG_SLACK", 100)
    png = _rgb16(3, 2, 3)
    path = tmp_path / "m.png"
    path.write_bytes(png)
    want = map_files.read_image(path)
    for size, refused in ((176, False), (177, True)):
        path.write_bytes(png + b"\0" * (size - len(png)))  # junk after IEND
        if refused:
            with pytest.raises(ValueError) as raised:
                map_files.read_image(path)
            assert str(raised.value) == (
                f"{path}: a PNG of 3 x 2 pixels with 16 bits per colour channel larger "
                "than 176 bytes (twice its samples and 100 bytes for other chunks): save "
                "it without the extra data"
            )
        else:
            grey, alpha = map_files.read_image(path)
            np.testing.assert_array_equal(grey, want[0])
            assert alpha is None and want[1] is None
