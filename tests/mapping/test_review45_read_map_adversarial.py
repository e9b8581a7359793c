"""``read_map``'s band-by-band conversion, attacked (review 45, READCHECK).

Commit 0c3d1a3 converts a map image to log-odds a band of about 2**18 pixels
at a time (``_Image.rows``, ``_band_logodds``) and claims the grids of the
whole-image conversion bit for bit. Checked against the parent commit's code
in separate processes (log-odds bytes, resolution, origin, thresholds, errors
and warnings; ``read_pgm`` and ``read_image``; the files untouched): 700
hypothesis draws over 23 image kinds (PGM P5 8/16-bit, odd ``maxval`` and P2;
PNG grey, grey + alpha, RGB, RGBA, palette with and without tRNS, tRNS keys at
8 and 16 bits, 1-bit, 16-bit grey, RGB, RGBA and grey + alpha; 32-bit TIFF,
CMYK TIFF, BMP, GIF), sizes 1 x 1 to 3 x (2**18 + 1), bands of 1 to 1000
pixels, thresholds at grey levels' probabilities, 0 and 1, every mode and
``negate``; every image kind truncated or with a flipped byte at each offset;
the three real maps with bands of 1, 7 and 37 pixels. No difference was found.
These tests keep what was checked, against the whole image read in one band
and against map_server's classes computed from the pixels.
"""

from __future__ import annotations

import struct
import zlib
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from test_review45_read_map_memory import _read_in_bands, _same_grid

import navkit.mapping.io._map_files as map_files
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map

_WIDE = 1 << 18  # _READ_BLOCK_PIXELS when written: wider images take one row a band


def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def _png(
    samples: np.ndarray,
    colour_type: int,
    depth: int,
    *,
    trns: bytes | None = None,
    plte: bytes | None = None,
) -> bytes:
    """A PNG of ``samples`` (rows, cols, channels), with the tRNS and PLTE chunks given.

    Written by hand: Pillow saves no 16-bit colour, and no tRNS key beside 16-bit grey.
    """
    rows = samples.shape[0]
    raster = samples.astype(">u2" if depth == 16 else np.uint8).reshape(rows, -1)
    lines = raster.view(np.uint8).reshape(rows, -1)
    raw = np.concatenate([np.zeros((rows, 1), np.uint8), lines], axis=1).tobytes()
    header = struct.pack(">IIBBBBB", samples.shape[1], rows, depth, colour_type, 0, 0, 0)
    return (
        b"\x89PNG\r\n\x1a\n"
        + _chunk(b"IHDR", header)
        + (_chunk(b"PLTE", plte) if plte is not None else b"")
        + (_chunk(b"tRNS", trns) if trns is not None else b"")
        + _chunk(b"IDAT", zlib.compress(raw, 1))
        + _chunk(b"IEND", b"")
    )


# Kinds the memory test (test_review45_read_map_memory) does not draw, and three it does.
_KINDS = (
    "p5", "p2", "rgb16", "rgba16", "la16", "grey16_key", "rgb16_key", "rgb_key", "P_trns", "1",
    "I32", "cmyk",
)  # fmt: skip


def _write_image(folder: Path, kind: str, samples: np.ndarray, maxval: int) -> str:
    """Image ``kind`` of ``samples`` (rows, cols, 4) of 0..65535; its file name."""
    rows, cols = samples.shape[:2]
    bytes8 = (samples >> 8).astype(np.uint8)
    if kind in ("p5", "p2"):
        levels = samples[..., 0] % (maxval + 1)
        head = f"{cols} {rows}\n{maxval}\n".encode()
        if kind == "p2":
            (folder / "m.pgm").write_bytes(
                b"P2\n" + head + " ".join(map(str, levels.ravel())).encode()
            )
        else:
            raster = levels.astype(np.uint8 if maxval < 256 else ">u2").tobytes()
            (folder / "m.pgm").write_bytes(b"P5\n" + head + raster)
        return "m.pgm"
    if kind in ("rgba16", "la16"):
        data = _png(samples[..., : 4 if kind == "rgba16" else 2], 6 if kind == "rgba16" else 4, 16)
    elif kind in ("rgb16", "rgb16_key", "grey16_key", "rgb_key"):
        grey = kind == "grey16_key"
        depth = 8 if kind == "rgb_key" else 16
        colour = (bytes8 if depth == 8 else samples)[..., : 1 if grey else 3]
        key = colour[-1, -1] if kind != "rgb16" else None
        trns = None if key is None else struct.pack(f">{len(key)}H", *map(int, key))
        data = _png(colour, 0 if grey else 2, depth, trns=trns)
    elif kind == "P_trns":
        palette = (np.arange(48, dtype=np.uint8) * 37).tobytes()
        alpha = np.array([0, 255, 128, 254] * 4, dtype=np.uint8).tobytes()
        data = _png(samples[..., :1] % 16, 3, 8, trns=alpha, plte=palette)
    else:
        image_module = pytest.importorskip("PIL.Image")
        if kind == "1":
            picture = image_module.fromarray(bytes8[..., 0] > 127)
        elif kind == "I32":
            # 32-bit, scaled by the whole image's peak: 0..255 but for a few
            # pixels up to 65535 (or none), negative ones clipped.
            values = np.where(samples[..., 1] < 3000, samples[..., 0], samples[..., 0] >> 8)
            picture = image_module.fromarray(values.astype(np.int32) - 2)
        else:
            picture = image_module.fromarray(bytes8).convert("CMYK")
        name = "m.png" if kind == "1" else "m.tif"
        picture.save(folder / name)
        return name
    (folder / "m.png").write_bytes(data)
    return "m.png"


def _write_yaml(folder: Path, image: str, mode: str, negate: int, occ: float, free: float) -> Path:
    path = folder / "m.yaml"
    path.write_text(
        f"image: {image}\nresolution: 0.05\norigin: [-1, 2, 3.5]\nnegate: {negate}\n"
        f"occupied_thresh: {occ!r}\nfree_thresh: {free!r}\nmode: {mode}\n"
    )
    return path


def _level_thresholds(levels: tuple[int, int], scale: float) -> tuple[float, float]:
    """Thresholds equal to the probabilities (``1 - v / scale``) of two grey levels."""
    high, low = sorted(1.0 - v / scale for v in levels)[::-1]
    if high > low:
        return high, low
    # One level twice: the free threshold just below it, or, at probability 0 (the
    # brightest level), the occupied one just above it (read_map refuses 0 and 0).
    if low >= 1 / 1024:
        return high, low - 1 / 1024
    return high + 1 / 1024, low


def test_level_thresholds_are_always_a_valid_pair() -> None:
    for scale in (255, 1020):
        for a in range(scale + 1):
            for b in (0, a // 2, a, scale):
                occ, free = _level_thresholds((a, b), float(scale))
                assert 0.0 <= free < occ <= 1.0, (a, b, scale)


_THRESHOLDS = st.one_of(
    st.sampled_from([(0.65, 0.196), (0.9995, 0.0005), (1.0, 0.0), (0.51, 0.5), (0.9, 0.6)]),
    st.tuples(st.integers(0, 255), st.integers(0, 255)).map(lambda t: _level_thresholds(t, 255.0)),
    # Grey and alpha averaged in trinary mode: (3 v + a) / 1020.
    st.tuples(st.integers(0, 1020), st.integers(0, 1020)).map(
        lambda t: _level_thresholds(t, 1020.0)
    ),
)
_SIZES = st.one_of(
    st.tuples(st.integers(1, 12), st.integers(1, 12)),
    st.tuples(st.just(1), st.integers(1, 300)),
    st.tuples(st.integers(1, 300), st.just(1)),
)


def _samples(rows: int, cols: int, seed: int, extremes: bool) -> np.ndarray:
    rng = np.random.default_rng(seed)
    if extremes:
        ends = np.array([0, 255, 256, 205 * 257, 254 * 257, 65280, 65535])
        return rng.choice(ends, (rows, cols, 4))
    return rng.integers(0, 65536, (rows, cols, 4))


def _check_bands(
    tmp_path: Path,
    kind: str,
    size: tuple[int, int],
    seed: int,
    extremes: bool,
    maxval: int,
    mode: str,
    negate: int,
    thresholds: tuple[float, float],
    bands: tuple[int, ...],
) -> None:
    folder = tmp_path / f"{kind}-{seed}-{size[0]}x{size[1]}-{mode}{negate}-{maxval}"
    folder.mkdir()
    image = _write_image(folder, kind, _samples(*size, seed, extremes), maxval)
    path = _write_yaml(folder, image, mode, negate, *thresholds)
    files = {p: p.read_bytes() for p in folder.iterdir()}
    whole = _read_in_bands(path, size[0] * size[1])
    for band in bands:
        _same_grid(whole, _read_in_bands(path, band))
    assert {p: p.read_bytes() for p in folder.iterdir()} == files


_CASES: dict[str, Any] = {
    "kind": st.sampled_from(_KINDS),
    "size": _SIZES,
    "seed": st.integers(0, 2**32 - 1),
    "extremes": st.booleans(),
    "maxval": st.sampled_from([1, 3, 7, 255, 300, 1000, 65535]),
    "mode": st.sampled_from(["trinary", "scale", "raw"]),
    "negate": st.integers(0, 1),
    "thresholds": _THRESHOLDS,
}


@settings(max_examples=40, deadline=None)
@given(band=st.integers(1, 40), **_CASES)
# A band of one row of a column image, and bands of one pixel.
@example(band=1, kind="grey16_key", size=(300, 1), seed=3, extremes=True, maxval=1,
         mode="trinary", negate=0, thresholds=(1.0, 0.0))  # fmt: skip
# GraphicsMagick's colormap: a PGM of at least maxval pixels, whatever a band holds.
@example(band=1, kind="p5", size=(20, 20), seed=5, extremes=False, maxval=300,
         mode="raw", negate=0, thresholds=(0.65, 0.196))  # fmt: skip
# Thresholds beyond the clipping: black and white moved back across them in one-row bands.
@example(band=1, kind="p5", size=(3, 4), seed=6, extremes=True, maxval=255,
         mode="trinary", negate=0, thresholds=(0.9995, 0.0005))  # fmt: skip
@example(band=7, kind="P_trns", size=(1, 300), seed=4, extremes=False, maxval=1,
         mode="scale", negate=1, thresholds=(0.51, 0.5))  # fmt: skip
def test_bands_give_the_whole_images_grid_on_more_kinds(
    tmp_path_factory: pytest.TempPathFactory, band: int, **case: Any
) -> None:
    # The band's rows: _READ_BLOCK_PIXELS // width, 1 when the band is narrower than a row.
    _check_bands(tmp_path_factory.mktemp("bands"), bands=(band, case["size"][1] + 1), **case)


@pytest.mark.slow
@settings(max_examples=400, deadline=None)
@given(band=st.integers(1, 200), **_CASES)
def test_bands_give_the_whole_images_grid_sweep(
    tmp_path_factory: pytest.TempPathFactory, band: int, **case: Any
) -> None:
    _check_bands(tmp_path_factory.mktemp("sweep"), bands=(1, 7, 37, band), **case)


def _trinary_classes(levels: np.ndarray, occ: float, free: float) -> np.ndarray:
    """map_server's trinary classes (1 occupied, 0 free, -1 unknown) of 8-bit grey, grid order."""
    p = 1.0 - levels / 255.0
    return np.where(p > occ, 1, np.where(p < free, 0, -1))[::-1]


def _classes(grid: OccupancyGrid) -> np.ndarray:
    return np.where(grid.occupied(), 1, np.where(grid.free(), 0, -1))


@pytest.mark.parametrize("width", [_WIDE - 1, _WIDE, _WIDE + 1, _WIDE // 2 + 1])
def test_wide_images_one_row_a_band(tmp_path: Path, width: int) -> None:
    # Above 2**17 pixels a row, a band is one row (2**18 // width == 1); above 2**18
    # a band is one row wider than the block.
    rows = 3
    levels = ((np.arange(rows * width) * 7) % 256).astype(np.uint8).reshape(rows, width)
    levels[0], levels[2, ::2] = 0, 254
    (tmp_path / "m.pgm").write_bytes(f"P5 {width} {rows} 255\n".encode() + levels.tobytes())
    path = _write_yaml(tmp_path, "m.pgm", "trinary", 0, 0.65, 0.196)
    banded = read_map(path)
    _same_grid(_read_in_bands(path, rows * width), banded)
    assert np.array_equal(_classes(banded), _trinary_classes(levels, 0.65, 0.196))
    # The image's top row is the grid's last row, band by band.
    assert banded.occupied()[-1].all()
    assert banded.free()[0, ::2].all()


@pytest.mark.parametrize("shape", [(1, 256), (256, 1), (16, 16)])
@pytest.mark.parametrize("band", [1, 5, 256])
def test_thresholds_at_grey_levels_class_as_map_server(
    tmp_path: Path, shape: tuple[int, int], band: int
) -> None:
    # Every 8-bit level once; thresholds exactly at levels' probabilities (a pixel
    # there is neither above nor below: unknown), at 0 and at 1.
    levels = np.arange(256, dtype=np.uint8).reshape(shape)
    (tmp_path / "m.pgm").write_bytes(f"P5 {shape[1]} {shape[0]} 255\n".encode() + levels.tobytes())
    for occ_level, free_level in [(0, 255), (50, 205), (101, 102), (254, 255), (0, 1)]:
        occ, free = 1.0 - occ_level / 255.0, 1.0 - free_level / 255.0
        for thresholds in [(occ, free), (1.0, free), (occ, 0.0)]:
            path = _write_yaml(tmp_path, "m.pgm", "trinary", 0, *thresholds)
            grid = _read_in_bands(path, band)
            assert np.array_equal(_classes(grid), _trinary_classes(levels, *thresholds)), thresholds


def _yaml_of(tmp_path: Path, name: str, data: bytes) -> Path:
    (tmp_path / name).write_bytes(data)
    return _write_yaml(tmp_path, name, "trinary", 0, 0.65, 0.196)


def _broken_images() -> dict[str, tuple[str, bytes, str]]:
    """Images cut short or changed, the name they are saved as, and what the error says."""
    rng = np.random.default_rng(45)
    rgba16 = _png(rng.integers(0, 65536, (9, 11, 4)), 6, 16)
    grey = _png(rng.integers(0, 256, (9, 11, 1)), 0, 8)
    return {
        "P5 short": ("m.pgm", b"P5 4 3 255\n" + bytes(11), "PGM raster truncated: 11 bytes"),
        "P5 16-bit odd": ("m.pgm", b"P5 2 1 65535\n\x00\x01\x02", "PGM raster truncated: 3"),
        "P2 short": ("m.pgm", b"P2 3 2 7\n1 2 3 4 5", "PGM raster truncated: 5 of 6 values"),
        "P2 over maxval": ("m.pgm", b"P2 2 1 7\n1 8", "PGM pixel values exceed maxval 7"),
        "PNG cut in IDAT": ("m.png", grey[: len(grey) - 40], "cannot read the image"),
        "16-bit PNG cut": ("m.png", rgba16[: len(rgba16) // 2], "cannot read the image"),
        "16-bit PNG bad IDAT": (
            "m.png",
            rgba16[:60] + bytes(b ^ 0x5A for b in rgba16[60:80]) + rgba16[80:],
            "cannot read the image",
        ),
    }


@pytest.mark.parametrize("case", list(_broken_images()))
def test_broken_images_raise_the_same_value_error_in_any_band(tmp_path: Path, case: str) -> None:
    pytest.importorskip("PIL")
    name, data, says = _broken_images()[case]
    path = _yaml_of(tmp_path, name, data)
    messages = set()
    for band in (1, 7, 1 << 18):
        with pytest.raises(ValueError, match="map image") as caught:
            _read_in_bands(path, band)
        messages.add(str(caught.value))
    (message,) = messages
    assert message.startswith(f"{path}: map image {tmp_path / name}: "), message
    assert says in message
    assert (tmp_path / name).read_bytes() == data


def test_a_16_bit_png_changed_between_its_two_decodings(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # A 16-bit colour PNG is decoded twice, from one copy of the file's bytes
    # (TILES): rewritten in place (23 KiB, beyond the reader's 8 KiB buffer) with
    # another size once it is copied, it reads as the file it was.
    image_module = pytest.importorskip("PIL.Image")
    rng = np.random.default_rng(1)
    first = _png(rng.integers(0, 65536, (60, 64, 3)), 2, 16)
    second = _png(rng.integers(0, 65536, (64, 60, 3)), 2, 16)
    path = _yaml_of(tmp_path, "m.png", first)
    want = read_map(path)
    opened: list[int] = []
    real_open: Callable[..., Any] = image_module.open

    def open_then_change(fp: Any, *args: Any, **kwargs: Any) -> Any:
        opened.append(1)
        if len(opened) == 2:
            with open(tmp_path / "m.png", "r+b") as fh:
                fh.write(second)
                fh.truncate()
        return real_open(fp, *args, **kwargs)

    monkeypatch.setattr(image_module, "open", open_then_change)
    _same_grid(read_map(path), want)
    assert len(opened) == 3
    assert (tmp_path / "m.png").read_bytes() == second


@pytest.mark.parametrize("maxval", [1, 3, 254, 255, 256, 1000, 65535])
def test_read_pgm_and_read_image_of_every_sample(tmp_path: Path, maxval: int) -> None:
    # read_pgm: the exact v * 255 / maxval; read_image: map_server's levels
    # (GraphicsMagick's colormap for an image of at least maxval pixels), the
    # grey levels read_map's bands are made of.
    values = np.arange(maxval + 1)
    raster = values.astype(np.uint8 if maxval < 256 else ">u2").tobytes()
    pgm = tmp_path / "m.pgm"
    pgm.write_bytes(f"P5 {maxval + 1} 1 {maxval}\n".encode() + raster)
    exact = map_files.read_pgm(pgm)
    assert exact.shape == (1, maxval + 1)
    assert np.array_equal(exact[0], values * (255.0 / maxval))
    assert exact[0, 0] == 0.0 and exact[0, -1] == 255.0
    grey, alpha = map_files.read_image(pgm)
    assert alpha is None
    if maxval in (255, 65535):
        assert grey.tobytes() == exact.tobytes()
    else:
        assert np.array_equal(grey[0], values * (65535 // maxval) * (255.0 / 65535.0))
    assert pgm.read_bytes()[-len(raster) :] == raster


def test_read_image_of_a_16_bit_rgb_key(tmp_path: Path) -> None:
    # A tRNS colour of 16-bit samples: transparent only where all 16 bits of the
    # three channels match (the high bytes alone match elsewhere too).
    pytest.importorskip("PIL")
    samples = np.array([[[1000, 2000, 3000], [1000, 2000, 3001], [1001, 2000, 3000]]])
    png = tmp_path / "m.png"
    png.write_bytes(_png(samples, 2, 16, trns=struct.pack(">3H", 1000, 2000, 3000)))
    grey, alpha = map_files.read_image(png)
    assert alpha is not None
    assert alpha.tolist() == [[0.0, 255.0, 255.0]]
    assert grey.tolist() == [[2000 / 257, 6001 / 3 / 257, 6001 / 3 / 257]]


def test_real_maps_read_the_same_in_bands_of_seven_and_thirty_seven(shared_data: Path) -> None:
    paths = sorted((shared_data / "ros-map-server-maps").glob("*/*.yaml"))
    assert paths
    for path in paths:
        whole = read_map(path)
        for band in (7, 37, whole.logodds.shape[1] + 1):
            _same_grid(whole, _read_in_bands(path, band))
