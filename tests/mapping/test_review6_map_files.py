"""Sixth review of the map_server files: thresholds beyond the grid's probability clipping."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map, write_map
from navkit.mapping.io._map_files import pgm_bytes, png_bytes

pytest.importorskip("PIL")


def _map_server_classes(
    grey: np.ndarray, alpha: np.ndarray | None, occ: float, free: float, mode: str
) -> np.ndarray:
    """Nav2 map_io's cells (100 / 0 / -1 for in-between or unknown), written independently."""
    p = 1.0 - grey / 255.0  # negate 0
    out = np.where(occ < p, 100, np.where(p < free, 0, -1))
    if mode == "scale" and alpha is not None:
        out = np.where(alpha != 255, -1, out)
    return out


def _grid_classes(grid: OccupancyGrid) -> np.ndarray:
    return np.where(grid.occupied(), 100, np.where(grid.free(), 0, -1))[::-1]


@pytest.mark.parametrize(
    ("occ", "free"),
    [(0.999, 0.001), (0.9995, 0.0005), (0.9999, 0.5), (0.5, 1e-6), (1.0, 0.0), (0.65, 0.196)],
)
@pytest.mark.parametrize("mode", ["trinary", "scale"])
def test_black_and_white_pixels_keep_their_class_near_the_limits(
    tmp_path: Path, occ: float, free: float, mode: str
) -> None:
    # Black is p = 1 and white p = 0: occupied above any occupied_thresh < 1 and
    # free below any free_thresh > 0, although the grid clips them to 0.999 / 0.001.
    grey = np.arange(256, dtype=np.uint8).reshape(16, 16)
    alpha = np.full_like(grey, 255)
    alpha[0, :4] = 0
    if mode == "trinary":
        (tmp_path / "m.pgm").write_bytes(pgm_bytes(grey))
        image, used_alpha = "m.pgm", None
    else:
        (tmp_path / "m.png").write_bytes(png_bytes(np.stack([grey, grey, grey, alpha], -1)))
        image, used_alpha = "m.png", alpha
    (tmp_path / "m.yaml").write_text(
        f"image: {image}\nmode: {mode}\nresolution: 0.5\norigin: [0, 0, 0]\nnegate: 0\n"
        f"occupied_thresh: {occ!r}\nfree_thresh: {free!r}\n"
    )
    grid = read_map(tmp_path / "m.yaml")
    want = _map_server_classes(grey.astype(float), used_alpha, occ, free, mode)
    np.testing.assert_array_equal(_grid_classes(grid), want)


_THRESHOLDS = st.one_of(
    st.floats(0.0, 1.0),
    st.sampled_from([0.0, 1.0, 0.5, 0.999, 0.001, 0.9995, 0.0005, 1e-9, 1.0 - 1e-9]),
)


@settings(
    max_examples=50,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture],
)
@given(
    a=_THRESHOLDS,
    b=_THRESHOLDS,
    mode=st.sampled_from(["trinary", "scale"]),
    logodds=st.lists(
        st.one_of(st.floats(-25.0, 25.0, width=32), st.sampled_from([0.0, 6.906755, -6.906755])),
        min_size=1,
        max_size=10,
    ),
)
def test_write_read_round_trip_keeps_classes_for_any_thresholds(
    tmp_path: Path, a: float, b: float, mode: str, logodds: list[float]
) -> None:
    free, occ = sorted((a, b))
    if not free < occ:
        return
    grid = OccupancyGrid(
        np.array([logodds], dtype=np.float32),
        resolution=0.1,
        occupied_thresh=occ,
        free_thresh=free,
    )
    try:
        write_map(grid, tmp_path / "m.yaml", mode=mode)
    except ValueError as exc:  # documented: a band holding no 8-bit grey level
        assert "no 8-bit grey level" in str(exc)
        return
    again = read_map(tmp_path / "m.yaml")
    for view in ("occupied", "free", "unknown"):
        np.testing.assert_array_equal(getattr(again, view)(), getattr(grid, view)(), err_msg=view)


test_write_read_round_trip_keeps_classes_for_any_thresholds_thoroughly = slow_twin(
    test_write_read_round_trip_keeps_classes_for_any_thresholds, max_examples=150
)


def _yaml_with(tmp_path: Path, line: str) -> Path:
    (tmp_path / "m.pgm").write_bytes(pgm_bytes(np.array([[0, 254]], dtype=np.uint8)))
    keys = {
        "image": "m.pgm",
        "resolution": "0.5",
        "origin": "[1, 2, 0]",
        "negate": "0",
        "occupied_thresh": "0.65",
        "free_thresh": "0.196",
    }
    key, _, value = line.partition(": ")
    keys[key] = value
    path = tmp_path / "m.yaml"
    path.write_text("".join(f"{k}: {v}\n" for k, v in keys.items()))
    return path


@pytest.mark.parametrize(
    ("line", "name"),
    [
        ("resolution: 1:20", "resolution"),  # YAML 1.1 sexagesimal: 80
        ("resolution: 1:20.5", "resolution"),
        ("resolution: 1_0", "resolution"),  # YAML 1.1 and Python: 10
        ("resolution: 0b1", "resolution"),  # YAML 1.1 binary: 1
        ("occupied_thresh: 0_0.9", "occupied_thresh"),
        ("resolution: '١'", "resolution"),  # Python's float() reads Arabic-Indic digits
    ],
)
def test_yaml_1_1_only_numbers_are_refused_not_misread(
    tmp_path: Path, line: str, name: str
) -> None:
    # yaml-cpp (map_server's YAML 1.2 parser) reads none of these as a number.
    with pytest.raises(ValueError, match=name):
        read_map(_yaml_with(tmp_path, line))


def test_leading_zero_number_reads_as_decimal_like_yaml_cpp(tmp_path: Path) -> None:
    # YAML 1.1 reads 010 as octal 8; yaml-cpp's double conversion reads 10.
    grid = read_map(_yaml_with(tmp_path, "resolution: 010"))
    assert grid.resolution == 10.0
    origin = read_map(_yaml_with(tmp_path, "origin: [-010, 0.5, 0]")).origin
    assert (origin.x, origin.y) == (-10.0, 0.5)


def test_extra_key_with_a_yaml_1_1_number_is_still_ignored(tmp_path: Path) -> None:
    path = _yaml_with(tmp_path, "resolution: 0.5")
    path.write_text(path.read_text() + "scale: 1:20\nsize: 1_000\n")
    assert read_map(path).resolution == 0.5


def _grey_png(values: np.ndarray, depth: int, transparent: int) -> bytes:
    """A grey PNG (colour type 0) of ``depth`` bits with a tRNS transparent grey."""
    import struct
    import zlib

    def chunk(kind: bytes, data: bytes) -> bytes:
        crc = struct.pack(">I", zlib.crc32(kind + data))
        return struct.pack(">I", len(data)) + kind + data + crc

    height, width = values.shape
    dtype = ">u2" if depth == 16 else "u1"
    rows = b"".join(b"\x00" + values[r].astype(dtype).tobytes() for r in range(height))
    header = struct.pack(">IIBBBBB", width, height, depth, 0, 0, 0, 0)
    return (
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", header)
        + chunk(b"tRNS", struct.pack(">H", transparent))
        + chunk(b"IDAT", zlib.compress(rows))
        + chunk(b"IEND", b"")
    )


@pytest.mark.parametrize("mode", ["trinary", "scale"])
@pytest.mark.parametrize("transparent", [0, 205, 254, 255])
def test_sixteen_bit_grey_png_with_a_transparent_grey_reads_like_the_eight_bit_one(
    tmp_path: Path, mode: str, transparent: int
) -> None:
    # The same picture at 8 and 16 bits (v and 257 v), each with the transparent
    # grey marked by tRNS: map_server reads both alike (the marked pixels unknown
    # in scale mode), so read_map must too.
    levels = np.array([[0, 100, 205, 254, 255, 128]], dtype=np.int64)
    grids = []
    for depth, scale in ((8, 1), (16, 257)):
        folder = tmp_path / str(depth)
        folder.mkdir()
        (folder / "m.png").write_bytes(_grey_png(levels * scale, depth, transparent * scale))
        (folder / "m.yaml").write_text(
            f"image: m.png\nmode: {mode}\nresolution: 0.5\norigin: [0, 0, 0]\nnegate: 0\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
        )
        grids.append(read_map(folder / "m.yaml"))
    eight, sixteen = grids
    for view in ("occupied", "free", "unknown"):
        np.testing.assert_array_equal(getattr(sixteen, view)(), getattr(eight, view)(), view)
    if mode == "scale":  # the transparent grey is unknown: log-odds 0
        marked = (levels == transparent)[::-1]
        assert np.all(sixteen.logodds[marked] == 0.0)
        assert np.all(eight.logodds[marked] == 0.0)
