"""Peak memory of building occupancy grids and reading map files (review 10).

Robots run navkit on small computers with large maps: a grid of N cells needs
its float32 log-odds (4 bytes a cell), a map read the image plus the grid. The
bounds below are peak NumPy allocations (tracemalloc) in bytes a cell, with
margin; the earlier code needed 16 (float32 log-odds), 33 (a boolean mask), 24
(probabilities), 49 (an 8-bit PGM map) and 56 (a 16-bit RGBA PNG map).
"""

from __future__ import annotations

import struct
import zlib
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from memory_peak import peak_bytes
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map

SIDE = 1000
CELLS = SIDE * SIDE


def _peak_per_cell(call: Callable[[], Any]) -> float:
    """Peak bytes a cell allocated while ``call`` runs (its result included)."""
    return peak_bytes(call)[0] / CELLS


def _mask() -> np.ndarray:
    rng = np.random.default_rng(0)
    return rng.random((SIDE, SIDE)) < 0.2


def test_constructor_does_not_widen_float32_logodds() -> None:
    logodds = np.where(_mask(), np.float32(2.0), np.float32(-2.0))
    per_cell = _peak_per_cell(lambda: OccupancyGrid(logodds, resolution=0.05))
    assert per_cell < 6.0  # the float32 copy it keeps, 4 bytes a cell


def test_copy_is_one_float32_array() -> None:
    grid = OccupancyGrid.from_occupancy(_mask(), resolution=0.05)
    per_cell = _peak_per_cell(grid.copy)
    assert per_cell < 6.0


def test_from_occupancy_has_no_float64_grids() -> None:
    mask = _mask()
    per_cell = _peak_per_cell(lambda: OccupancyGrid.from_occupancy(mask, resolution=0.05))
    assert per_cell < 10.0  # the log-odds and the grid's own copy of them


def test_from_probabilities_has_no_float64_temporaries_of_the_grid_size() -> None:
    prob = np.where(_mask(), 0.9, 0.1)
    per_cell = _peak_per_cell(lambda: OccupancyGrid.from_probabilities(prob, resolution=0.05))
    assert per_cell < 12.0


def _yaml(folder: Path, image: str) -> Path:
    path = folder / f"{image}.yaml"
    path.write_text(
        f"image: {image}\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    return path


def test_pgm_map_read_needs_the_image_and_the_grid(tmp_path: Path) -> None:
    pixels = np.where(_mask(), 0, 254).astype(np.uint8)
    pixels[:, ::7] = 205
    (tmp_path / "m.pgm").write_bytes(f"P5\n{SIDE} {SIDE}\n255\n".encode() + pixels.tobytes())
    yaml = _yaml(tmp_path, "m.pgm")
    per_cell = _peak_per_cell(lambda: read_map(yaml))
    assert per_cell < 26.0


def _png16_rgba(pixels: np.ndarray) -> bytes:
    rows, cols, _ = pixels.shape
    raw = b"".join(b"\x00" + row.astype(">u2").tobytes() for row in pixels)

    def chunk(kind: bytes, data: bytes) -> bytes:
        crc = zlib.crc32(kind + data) & 0xFFFFFFFF
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", crc)

    header = struct.pack(">IIBBBBB", cols, rows, 16, 6, 0, 0, 0)
    return (
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", header)
        + chunk(b"IDAT", zlib.compress(raw, 1))
        + chunk(b"IEND", b"")
    )


def test_sixteen_bit_rgba_png_map_read(tmp_path: Path) -> None:
    pytest.importorskip("PIL")
    rgba = np.empty((SIDE, SIDE, 4), dtype=np.uint16)
    rgba[..., :3] = np.where(_mask(), 0, 65535)[..., None]
    rgba[..., 3] = 65535
    (tmp_path / "m.png").write_bytes(_png16_rgba(rgba))
    yaml = _yaml(tmp_path, "m.png")
    per_cell = _peak_per_cell(lambda: read_map(yaml))
    assert per_cell < 36.0
