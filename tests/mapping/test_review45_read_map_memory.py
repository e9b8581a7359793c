"""``read_map`` converts an image a band of rows at a time (review 45).

It widened the whole image to float64 grey levels (8 bytes a pixel), then to
float64 probabilities (8 more) beside boolean masks: 20 bytes a pixel at its
peak with the grid for an 8-bit PGM or grey PNG (5 GiB at
``OccupancyGrid.MAX_CELLS``) and 28 (tracemalloc; 32 counting Pillow's own
buffers, 9 GiB) for a PNG with 16-bit colour channels. Every step from a
pixel's samples to its log-odds depends on that pixel alone (and on the
image's size: GraphicsMagick's colormap for a PGM of at least ``maxval``
pixels), so the grey levels, probabilities and log-odds are now computed a
band of rows at a time into the grid's log-odds: the decoded image, the grid
and a band. Checked: the same log-odds bit for bit with one band (what the
whole image went through before) and with bands of a few pixels, on images of
every kind read and on the real maps; the memory tests fail on the parent
(20.00 and 28.00 bytes a pixel).
"""

from __future__ import annotations

import struct
import tempfile
import zlib
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from test_review9_map_16bit_colour import _chunk, _png16

import navkit.mapping.io._map_files as map_files
from memory_peak import peak_bytes
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map

_KINDS = ("p5", "p5_16", "p5_maxval", "p2", "L", "LA", "RGB", "RGBA", "P", "L_key", "I16")
_KINDS_16 = ("rgba16", "rgb16", "la16")
_THRESHOLDS = [(0.65, 0.196), (0.9995, 0.0005), (0.9, 0.6), (0.4, 0.1), (1.0, 0.0)]


def _write_image(folder: Path, kind: str, rows: int, cols: int, seed: int, maxval: int) -> str:
    rng = np.random.default_rng(seed)
    levels = rng.integers(0, 256, (rows, cols)).astype(np.uint8)
    levels[rng.random((rows, cols)) < 0.3] = 205
    head = f"{cols} {rows}\n".encode()
    if kind == "p5":
        (folder / "m.pgm").write_bytes(b"P5\n" + head + b"255\n" + levels.tobytes())
        return "m.pgm"
    if kind in ("p5_16", "p5_maxval", "p2"):
        top = 65535 if kind == "p5_16" else maxval
        samples = rng.integers(0, top + 1, (rows, cols))
        if kind == "p2":
            raster = " ".join(map(str, samples.ravel())).encode() + b"\n"
        else:
            raster = samples.astype(np.uint8 if top < 256 else ">u2").tobytes()
        magic = b"P2\n" if kind == "p2" else b"P5\n"
        (folder / "m.pgm").write_bytes(magic + head + f"{top}\n".encode() + raster)
        return "m.pgm"
    if kind in _KINDS_16:
        channels = {"rgba16": 4, "rgb16": 3, "la16": 2}[kind]
        samples = rng.integers(0, 65536, (rows, cols, channels))
        samples[..., -1] = rng.choice([0, 30000, 65535], (rows, cols))
        colour_type = {"rgba16": 6, "rgb16": 2, "la16": 4}[kind]
        (folder / "m.png").write_bytes(_png16(samples, colour_type))
        return "m.png"
    image = pytest.importorskip("PIL.Image")
    colour = rng.integers(0, 256, (rows, cols, 4)).astype(np.uint8)
    colour[..., 3] = rng.choice([0, 128, 255], (rows, cols))
    picture = {
        "L": lambda: image.fromarray(levels, "L"),
        "L_key": lambda: image.fromarray(levels, "L"),
        "LA": lambda: image.fromarray(colour[..., [0, 3]], "LA"),
        "RGB": lambda: image.fromarray(colour[..., :3], "RGB"),
        "RGBA": lambda: image.fromarray(colour, "RGBA"),
        "P": lambda: image.fromarray(colour[..., :3], "RGB").convert("P"),
        "I16": lambda: image.fromarray(levels.astype(np.uint16) * 257 + 3),  # mode I;16
    }[kind]()
    extra = {"transparency": int(levels.flat[0])} if kind == "L_key" else {}
    picture.save(folder / "m.png", **extra)
    return "m.png"


def _write_yaml(folder: Path, image: str, mode: str, negate: int, th: tuple[float, float]) -> Path:
    path = folder / "m.yaml"
    path.write_text(
        f"image: {image}\nresolution: 0.05\norigin: [1, 2, 0.3]\nnegate: {negate}\n"
        f"occupied_thresh: {th[0]}\nfree_thresh: {th[1]}\nmode: {mode}\n"
    )
    return path


def _read_in_bands(path: Path, band_pixels: int) -> OccupancyGrid:
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(map_files, "_READ_BLOCK_PIXELS", band_pixels)
        return read_map(path)


def _same_grid(a: OccupancyGrid, b: OccupancyGrid) -> None:
    assert a.logodds.dtype == b.logodds.dtype == np.float32
    assert a.logodds.tobytes() == b.logodds.tobytes()
    assert (a.resolution, a.origin) == (b.resolution, b.origin)
    assert (a.occupied_thresh, a.free_thresh) == (b.occupied_thresh, b.free_thresh)


@settings(max_examples=120, deadline=None)
@given(
    kind=st.sampled_from(_KINDS + _KINDS_16),
    rows=st.integers(1, 30),
    cols=st.integers(1, 30),
    seed=st.integers(0, 2**32 - 1),
    maxval=st.sampled_from([1, 3, 100, 255, 300, 1000, 4095, 65535]),
    mode=st.sampled_from(["trinary", "scale", "raw"]),
    negate=st.integers(0, 1),
    thresholds=st.sampled_from(_THRESHOLDS),
    band_pixels=st.integers(1, 64),
)
# GraphicsMagick's colormap applies to a PGM of at least maxval pixels (900 >= 300),
# whatever a band of one 30-pixel row holds.
@example(kind="p5_maxval", rows=30, cols=30, seed=1, maxval=300, mode="raw", negate=0,
         thresholds=_THRESHOLDS[0], band_pixels=1)  # fmt: skip
@example(kind="rgba16", rows=30, cols=30, seed=2, maxval=255, mode="trinary", negate=1,
         thresholds=_THRESHOLDS[1], band_pixels=7)  # fmt: skip
def test_bands_give_the_whole_images_grid_bit_for_bit(
    kind: str,
    rows: int,
    cols: int,
    seed: int,
    maxval: int,
    mode: str,
    negate: int,
    thresholds: tuple[float, float],
    band_pixels: int,
) -> None:
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        image = _write_image(folder, kind, rows, cols, seed, maxval)
        path = _write_yaml(folder, image, mode, negate, thresholds)
        whole = _read_in_bands(path, rows * cols)  # one band: the image at once
        _same_grid(whole, _read_in_bands(path, band_pixels))


def test_real_maps_read_the_same_in_bands_and_as_map_server_classes(shared_data: Path) -> None:
    paths = sorted((shared_data / "ros-map-server-maps").glob("*/*.yaml"))
    assert paths
    for path in paths:
        grid = read_map(path)
        _same_grid(grid, _read_in_bands(path, 1))
        # The classes of map_server's trinary reading of the 8-bit PGMs, from the bytes.
        meta = map_files.read_map_yaml(path)
        data = meta.image.read_bytes()
        _, width, height, maxval, offset = map_files._pgm_header(data, meta.image)
        assert maxval == 255 and not meta.negate and meta.mode == "trinary"
        levels = np.frombuffer(data, np.uint8, width * height, offset).reshape(height, width)
        p = 1.0 - levels / 255.0
        occupied, free = p > meta.occupied_thresh, p < meta.free_thresh
        assert np.array_equal(grid.occupied(), occupied[::-1]), path
        assert np.array_equal(grid.free(), free[::-1]), path
        assert np.array_equal(grid.unknown(), (~occupied & ~free)[::-1]), path


def _map(folder: Path, kind: str, side: int) -> Path:
    rng = np.random.default_rng(45)
    levels = rng.choice(np.array([0, 205, 254, 100], dtype=np.uint8), (side, side))
    head = f"{side} {side}\n".encode()
    if kind == "p5":
        (folder / "m.pgm").write_bytes(b"P5\n" + head + b"255\n" + levels.tobytes())
    elif kind == "p5_16":
        raster = (levels.astype(np.uint16) * 257).astype(">u2").tobytes()
        (folder / "m.pgm").write_bytes(b"P5\n" + head + b"65535\n" + raster)
    else:
        rgba = np.repeat(levels.astype(np.uint16)[..., None] * 257, 4, axis=2)
        rgba[..., 3] = 65535
        # _png16's rows, filter byte 0 each, joined at once (its += is quadratic).
        rows = rgba.astype(">u2").reshape(side, -1).view(np.uint8)
        raw = np.concatenate([np.zeros((side, 1), np.uint8), rows], axis=1).tobytes()
        header = struct.pack(">IIBBBBB", side, side, 16, 6, 0, 0, 0)
        (folder / "m.png").write_bytes(
            b"\x89PNG\r\n\x1a\n"
            + _chunk(b"IHDR", header)
            + _chunk(b"IDAT", zlib.compress(raw, 1))
            + _chunk(b"IEND", b"")
        )
    return _write_yaml(
        folder, "m.png" if kind == "rgba16" else "m.pgm", "trinary", 0, (0.65, 0.196)
    )


@pytest.mark.parametrize(
    ("kind", "per_pixel"),
    # The grid's 4 bytes and the decoded samples: 1, 2, and 8 (16-bit RGBA) with
    # Pillow's 8-bit decodings (whose own buffers tracemalloc does not see).
    [("p5", 6), ("p5_16", 7), ("rgba16", 17)],
)
def test_read_map_takes_the_image_the_grid_and_a_band(
    tmp_path: Path, kind: str, per_pixel: int
) -> None:
    if kind == "rgba16":
        pytest.importorskip("PIL")
    side = 2048
    path = _map(tmp_path, kind, side)
    peak, grid = peak_bytes(lambda: read_map(path))
    assert grid.logodds.shape == (side, side)
    # 20, 20 and 28 bytes a pixel before.
    assert peak < per_pixel * side * side + (12 << 20), f"{peak / side**2:.2f} bytes a pixel"
