"""ROS map_server files: the map YAML, PGM images and (with Pillow) other images (private).

Only the flat ``key: value`` YAML that map_server writes is understood (scalars,
quoted strings and ``[a, b, c]`` lists), so navkit needs no YAML library.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "MapMetadata",
    "pixel_occupancy",
    "read_image",
    "read_map_yaml",
    "read_pgm",
    "write_map_yaml",
    "write_pgm",
]

_MODES = ("trinary", "scale", "raw")
_REQUIRED = ("image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh")


@dataclass(frozen=True, slots=True)
class MapMetadata:
    """Content of a map_server YAML file (``image`` resolved against the YAML's folder)."""

    image: Path
    resolution: float
    origin: tuple[float, float, float]
    negate: bool
    occupied_thresh: float
    free_thresh: float
    mode: str


def _parse_scalar(text: str) -> str | list[str]:
    text = text.strip()
    if len(text) >= 2 and text[0] == text[-1] and text[0] in "'\"":
        return text[1:-1]
    if text.startswith("["):
        if not text.endswith("]"):
            raise ValueError(f"unterminated list {text!r}")
        return [item.strip() for item in text[1:-1].split(",") if item.strip()]
    return text


def _strip_comment(line: str) -> str:
    # A '#' starts a comment at the line start or after whitespace (YAML rule),
    # so '#' inside a file name such as 'map#2.pgm' is kept.
    for i, ch in enumerate(line):
        if ch == "#" and (i == 0 or line[i - 1] in " \t"):
            return line[:i]
    return line


def _as_float(value: str | list[str], key: str, path: Path) -> float:
    if isinstance(value, list):
        raise ValueError(f"{path}: {key} must be a number, got a list")
    try:
        out = float(value)
    except ValueError:
        raise ValueError(f"{path}: {key} must be a number, got {value!r}") from None
    if not math.isfinite(out):
        raise ValueError(f"{path}: {key} must be finite, got {value!r}")
    return out


def read_map_yaml(path: str | os.PathLike[str]) -> MapMetadata:
    """Parse a map_server YAML file and check every required key.

    Raises
    ------
    FileNotFoundError
        The YAML or the image it names does not exist.
    ValueError
        A line is not ``key: value``, a required key is missing, or a value is
        out of range (resolution <= 0, thresholds outside (0, 1) or
        ``free_thresh >= occupied_thresh``, unknown ``mode``).
    """
    yaml_path = Path(path)
    if not yaml_path.is_file():
        raise FileNotFoundError(f"map YAML file {yaml_path} does not exist")
    entries: dict[str, str | list[str]] = {}
    text = yaml_path.read_text(encoding="utf-8")
    for number, raw in enumerate(text.splitlines(), start=1):
        line = _strip_comment(raw).strip()
        if not line or line == "---":
            continue
        key, sep, value = line.partition(":")
        if not sep or not key.strip() or " " in key.strip():
            raise ValueError(f"{yaml_path}:{number}: expected 'key: value', got {raw.strip()!r}")
        try:
            entries[key.strip()] = _parse_scalar(value)
        except ValueError as exc:
            raise ValueError(f"{yaml_path}:{number}: {exc}") from None
    missing = [key for key in _REQUIRED if key not in entries]
    if missing:
        raise ValueError(f"{yaml_path}: missing required key(s) {', '.join(missing)}")

    image = entries["image"]
    if isinstance(image, list) or not image:
        raise ValueError(f"{yaml_path}: image must be a file name, got {image!r}")
    image_path = Path(image)
    if not image_path.is_absolute():
        image_path = yaml_path.parent / image_path
    if not image_path.is_file():
        raise FileNotFoundError(f"{yaml_path}: map image {image_path} does not exist")

    resolution = _as_float(entries["resolution"], "resolution", yaml_path)
    if resolution <= 0.0:
        raise ValueError(f"{yaml_path}: resolution must be > 0, got {resolution}")
    origin_raw = entries["origin"]
    if not isinstance(origin_raw, list) or len(origin_raw) != 3:
        raise ValueError(f"{yaml_path}: origin must be a list [x, y, yaw], got {origin_raw!r}")
    ox, oy, oyaw = (_as_float(v, "origin", yaml_path) for v in origin_raw)
    negate_raw = entries["negate"]
    if isinstance(negate_raw, list) or negate_raw.lower() not in ("0", "1", "true", "false"):
        raise ValueError(f"{yaml_path}: negate must be 0 or 1, got {negate_raw!r}")
    negate = negate_raw.lower() in ("1", "true")
    occ = _as_float(entries["occupied_thresh"], "occupied_thresh", yaml_path)
    free = _as_float(entries["free_thresh"], "free_thresh", yaml_path)
    if not (0.0 <= free < occ <= 1.0):
        raise ValueError(
            f"{yaml_path}: need 0 <= free_thresh < occupied_thresh <= 1, got "
            f"free_thresh={free}, occupied_thresh={occ}"
        )
    mode = entries.get("mode", "trinary")
    if isinstance(mode, list) or mode.lower() not in _MODES:
        raise ValueError(f"{yaml_path}: mode must be one of {', '.join(_MODES)}, got {mode!r}")
    return MapMetadata(image_path, resolution, (ox, oy, oyaw), negate, occ, free, mode.lower())


def write_map_yaml(path: Path, meta: MapMetadata) -> None:
    """Write ``meta`` as a map_server YAML (image stored relative when beside the YAML)."""
    image = meta.image.name if meta.image.parent == path.parent else str(meta.image)
    ox, oy, oyaw = meta.origin
    path.write_text(
        f"image: {image}\n"
        f"mode: {meta.mode}\n"
        f"resolution: {meta.resolution!r}\n"
        f"origin: [{ox!r}, {oy!r}, {oyaw!r}]\n"
        f"negate: {int(meta.negate)}\n"
        f"occupied_thresh: {meta.occupied_thresh!r}\n"
        f"free_thresh: {meta.free_thresh!r}\n",
        encoding="utf-8",
    )


def _pgm_header(data: bytes, path: Path) -> tuple[str, int, int, int, int]:
    """Parse magic, width, height, maxval; return them and the raster offset."""
    if data[:2] not in (b"P5", b"P2"):
        raise ValueError(f"{path}: not a PGM image (magic {data[:2]!r}, expected P5 or P2)")
    fields: list[int] = []
    pos = 2
    n = len(data)
    while len(fields) < 3:
        while pos < n and data[pos : pos + 1].isspace():
            pos += 1
        if pos < n and data[pos : pos + 1] == b"#":
            while pos < n and data[pos : pos + 1] not in (b"\n", b"\r"):
                pos += 1
            continue
        start = pos
        while pos < n and not data[pos : pos + 1].isspace() and data[pos : pos + 1] != b"#":
            pos += 1
        token = data[start:pos]
        if not token:
            raise ValueError(f"{path}: PGM header ends before width, height and maxval")
        if not token.isdigit():
            raise ValueError(f"{path}: bad PGM header field {token!r} (expected an integer)")
        fields.append(int(token))
    width, height, maxval = fields
    if width <= 0 or height <= 0:
        raise ValueError(f"{path}: PGM size must be positive, got {width} x {height}")
    if not 0 < maxval < 65536:
        raise ValueError(f"{path}: PGM maxval must be in 1..65535, got {maxval}")
    if pos >= n or not data[pos : pos + 1].isspace():
        raise ValueError(f"{path}: PGM header must end with one whitespace byte after maxval")
    return data[:2].decode(), width, height, maxval, pos + 1


def read_pgm(path: str | os.PathLike[str]) -> NDArray[np.float64]:
    """Read a binary (P5) or ASCII (P2) PGM image as grey levels scaled to 0..255.

    Returns a float64 array of shape (height, width) in file order (row 0 is the
    top of the image).
    """
    pgm = Path(path)
    data = pgm.read_bytes()
    magic, width, height, maxval, offset = _pgm_header(data, pgm)
    count = width * height
    if magic == "P5":
        dtype = np.dtype(np.uint8) if maxval < 256 else np.dtype(">u2")
        need = count * dtype.itemsize
        if len(data) - offset < need:
            raise ValueError(
                f"{pgm}: PGM raster truncated: {len(data) - offset} bytes for "
                f"{width} x {height} pixels ({need} bytes needed)"
            )
        pixels = np.frombuffer(data, dtype=dtype, count=count, offset=offset).astype(np.int64)
    else:
        tokens = data[offset:].split()
        if len(tokens) < count:
            raise ValueError(f"{pgm}: PGM raster truncated: {len(tokens)} of {count} values")
        try:
            pixels = np.array([int(t) for t in tokens[:count]], dtype=np.int64)
        except ValueError:
            raise ValueError(f"{pgm}: P2 raster holds a non-integer value") from None
    if pixels.size and (pixels.min() < 0 or pixels.max() > maxval):
        raise ValueError(f"{pgm}: PGM pixel values exceed maxval {maxval}")
    return pixels.reshape(height, width).astype(np.float64) * (255.0 / maxval)


def write_pgm(path: Path, pixels: NDArray[np.uint8]) -> None:
    """Write an 8-bit binary (P5) PGM; ``pixels`` row 0 is the top of the image."""
    height, width = pixels.shape
    header = f"P5\n# CREATOR: navkit\n{width} {height}\n255\n".encode("ascii")
    path.write_bytes(header + np.ascontiguousarray(pixels, dtype=np.uint8).tobytes())


def _read_with_pillow(path: Path) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    try:
        from PIL import Image
    except ImportError:
        raise ImportError(
            f"reading the map image {path.name} needs Pillow (only PGM is read without "
            "it); install it with `pip install pillow`"
        ) from None
    with Image.open(path) as img:
        if img.mode not in ("L", "LA", "RGB", "RGBA", "I", "I;16", "P", "1"):
            img = img.convert("RGBA")
        if img.mode in ("P", "1"):
            img = img.convert("RGBA" if "transparency" in img.info else "L")
        arr = np.asarray(img)
        mode = img.mode
    if mode in ("I", "I;16"):
        peak = 65535.0 if arr.max(initial=0) > 255 else 255.0
        return arr.astype(np.float64) * (255.0 / peak), None
    if arr.ndim == 2:
        return arr.astype(np.float64), None
    has_alpha = mode in ("LA", "RGBA")
    colour = arr[..., :-1] if has_alpha else arr
    grey = colour.astype(np.float64).mean(axis=2)
    alpha = arr[..., -1].astype(np.float64) if has_alpha else None
    return grey, alpha


def read_image(path: Path) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """Grey levels 0..255 (averaged over colour channels) and alpha (or None) of an image.

    PGM files are read with numpy; anything else needs Pillow.
    """
    with path.open("rb") as fh:
        magic = fh.read(2)
    if magic in (b"P5", b"P2"):
        return read_pgm(path), None
    if path.suffix.lower() == ".pgm":
        raise ValueError(f"{path}: not a PGM image (magic {magic!r}, expected P5 or P2)")
    return _read_with_pillow(path)


def pixel_occupancy(
    grey: NDArray[np.float64],
    alpha: NDArray[np.float64] | None,
    meta: MapMetadata,
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """map_server's reading of pixels: occupancy probability and unknown mask.

    With ``negate`` 0, ``p = (255 - v) / 255``. In ``trinary`` mode a pixel is
    occupied (p = 1) above ``occupied_thresh``, free (p = 0) below ``free_thresh``
    and unknown otherwise. ``scale`` keeps ``p`` itself for the in-between pixels
    and makes non-opaque ones unknown; ``raw`` reads the grey value directly as a
    percentage (values above 100 are unknown). Rows are in image order.
    """
    if meta.mode == "raw":
        value = np.rint(grey)
        unknown = value > 100
        return np.where(unknown, 0.5, value / 100.0), unknown
    p = grey / 255.0 if meta.negate else (255.0 - grey) / 255.0
    occupied = p > meta.occupied_thresh
    free = p < meta.free_thresh
    between = ~occupied & ~free
    if meta.mode == "trinary":
        prob = np.where(occupied, 1.0, np.where(free, 0.0, 0.5))
        return prob, between
    unknown = between & (alpha < 255.0) if alpha is not None else np.zeros_like(between)
    prob = np.where(occupied, 1.0, np.where(free, 0.0, p))
    return prob, unknown

