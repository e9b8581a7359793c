"""Map images classed as ROS's own map_server classes them (review 27, ROS conventions).

Two reference rules, re-implemented from their source (read, not copied):

* Nav2 up to Iron, ``ros-navigation/navigation2`` ``nav2_map_server/src/map_io.cpp``
  (branch ``humble``, 3c3db59d): ``double shade =
  Magick::ColorGray::scaleQuantumToDouble(sum / channels.size());``, ``double occ =
  (load_parameters.negate ? shade : 1.0 - shade);``, then ``if
  (load_parameters.occupied_thresh < occ)`` occupied, ``else if (occ <
  load_parameters.free_thresh)`` free, else unknown; in trinary mode
  ``channels.push_back(MaxRGB - pixel.alphaQuantum());`` averages alpha in.
* Nav2 from Jazzy on, the same file (branch ``jazzy``, f4108e5b):
  ``gray.type(Magick::GrayscaleType);`` then ``gray_matrix.cast<float>() / 255.0f``,
  ``(normalized.array() >= load_parameters.occupied_thresh)``, ``(normalized.array()
  <= load_parameters.free_thresh)`` and ``(alpha_array < 255).select(
  nav2_util::OCC_GRID_UNKNOWN, result)`` in every mode.

navkit follows the first exactly; its docs must say where the second differs.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from numpy.typing import NDArray

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map, write_map
from navkit.mapping.io._map_files import pgm_bytes, pixel_occupancy, read_image, read_map_yaml

OCCUPIED, FREE, UNKNOWN = 100, 0, -1


def _humble(
    grey: NDArray[np.float64],
    alpha: NDArray[np.float64] | None,
    occ_t: float,
    free_t: float,
    negate: bool,
    mode: str,
) -> NDArray[np.int64]:
    # GraphicsMagick Q16: an 8-bit channel v is the quantum v * 257 of MaxRGB 65535.
    if mode == "trinary" and alpha is not None:
        shade = ((3.0 * grey * 257.0 + alpha * 257.0) / 4.0) / 65535.0
    else:
        shade = (grey * 257.0) / 65535.0
    occ = shade if negate else 1.0 - shade
    out = np.where(occ_t < occ, OCCUPIED, np.where(occ < free_t, FREE, UNKNOWN))
    if mode == "scale" and alpha is not None:
        out = np.where(alpha < 255.0, UNKNOWN, out)
    return out


def _jazzy(
    grey: NDArray[np.float64],
    alpha: NDArray[np.float64] | None,
    occ_t: float,
    free_t: float,
    negate: bool,
) -> NDArray[np.int64]:
    # Grey images only (luminance of r = g = b is the grey itself).
    n = grey.astype(np.float32) / np.float32(255.0)
    if not negate:
        n = np.float32(1.0) - n
    out = np.full(n.shape, UNKNOWN)
    out[n >= np.float32(occ_t)] = OCCUPIED
    out[n <= np.float32(free_t)] = FREE
    if alpha is not None:
        out[alpha < 255.0] = UNKNOWN
    return out


def _classes(grid: OccupancyGrid) -> NDArray[np.int64]:
    """The grid's classes in image row order (top row first)."""
    cls = np.where(grid.occupied(), OCCUPIED, np.where(grid.free(), FREE, UNKNOWN))
    return np.asarray(cls[::-1])


def _write(
    folder: Path, pixels: NDArray[np.uint8], occ_t: float, free_t: float, negate: bool
) -> Path:
    (folder / "m.pgm").write_bytes(pgm_bytes(pixels))
    yaml = folder / "m.yaml"
    yaml.write_text(
        f"image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: {int(negate)}\n"
        f"occupied_thresh: {occ_t!r}\nfree_thresh: {free_t!r}\n"
    )
    return yaml


@pytest.mark.parametrize(
    ("occ_t", "free_t"),
    # map_saver's, Nav2's old default, ties at 102 / 153 / 51 / 204, and the ends.
    [(0.65, 0.196), (0.65, 0.25), (0.6, 0.4), (0.65, 0.2), (1.0, 0.196), (0.65, 0.0)],
)
@pytest.mark.parametrize("negate", [False, True])
def test_every_grey_level_is_classed_as_nav2_humble_classes_it(
    tmp_path: Path, occ_t: float, free_t: float, negate: bool
) -> None:
    levels = np.arange(256, dtype=np.uint8).reshape(16, 16)
    grid = read_map(_write(tmp_path, levels, occ_t, free_t, negate))
    want = _humble(levels.astype(np.float64), None, occ_t, free_t, negate, "trinary")
    np.testing.assert_array_equal(_classes(grid), want)


def test_the_documented_jazzy_differences_are_real(tmp_path: Path) -> None:
    # occupied_thresh 1: black is occupied to Jazzy (>=), to nobody here nor in Humble.
    black_white = np.array([[0, 255]], dtype=np.uint8)
    grid = read_map(_write(tmp_path, black_white, 1.0, 0.0, False))
    grey = black_white.astype(np.float64)
    assert _classes(grid).tolist() == [[UNKNOWN, UNKNOWN]]
    assert _jazzy(grey, None, 1.0, 0.0, False).tolist() == [[OCCUPIED, FREE]]
    # An opaque 205 grey in trinary mode with an alpha channel: alpha averaged in
    # ((3 * 205 + 255) / 4 = 217.5) makes it free, as in Humble; Jazzy: unknown.
    meta = read_map_yaml(_write(tmp_path, black_white, 0.65, 0.196, False))
    g, a = np.array([[205.0]]), np.array([[255.0]])
    prob, unknown = pixel_occupancy(g, a, meta)
    assert not unknown[0, 0] and prob[0, 0] == 0.0
    assert _humble(g, a, 0.65, 0.196, False, "trinary")[0, 0] == FREE
    assert _jazzy(g, a, 0.65, 0.196, False)[0, 0] == UNKNOWN


def test_read_map_docs_say_which_nav2_rule_they_follow() -> None:
    doc = read_map.__doc__ or ""
    assert "humble" in doc and "Jazzy" in doc
    for difference in ("``>=``", "luminance", "not fully opaque", "occupied_thresh: 1"):
        assert difference in doc, difference


@pytest.mark.parametrize("name", ["turtlebot3_world", "willow_garage_2010", "lse_arena"])
def test_real_maps_read_and_written_as_both_nav2_rules_read_them(
    shared_data: Path, tmp_path: Path, name: str
) -> None:
    pytest.importorskip("PIL")
    (yaml,) = (shared_data / "ros-map-server-maps" / name).glob("*.yaml")
    meta = read_map_yaml(yaml)
    grid = read_map(yaml)
    classes = _classes(grid)
    grey, alpha = read_image(meta.image)
    args = (meta.occupied_thresh, meta.free_thresh, meta.negate)
    np.testing.assert_array_equal(classes, _humble(grey, alpha, *args, "trinary"))
    np.testing.assert_array_equal(classes, _jazzy(grey, alpha, *args))
    for mode in ("trinary", "scale"):
        image = write_map(grid, tmp_path / f"{mode}.yaml", mode=mode)
        saved = read_map_yaml(tmp_path / f"{mode}.yaml")
        grey, alpha = read_image(image)
        args = (saved.occupied_thresh, saved.free_thresh, saved.negate)
        by_humble = _humble(grey, alpha, *args, mode)
        # Scale mode's in-between values (1..99) are neither occupied nor free.
        by_humble = np.where((by_humble == OCCUPIED) | (by_humble == FREE), by_humble, UNKNOWN)
        np.testing.assert_array_equal(by_humble, classes)
        np.testing.assert_array_equal(_jazzy(grey, alpha, *args), classes)
