"""read_map: a warning Pillow gives on a damaged image is the file's ValueError (review 50, FOUND2).

A TIFF cut after its header, or its LZW strip cut short, makes Pillow warn
"Corrupt EXIF data" before it gives up. Under ``-W error`` (navkit's own test
settings, and many users' test suites) that warning escaped ``read_map`` as a
``UserWarning`` instead of the ``ValueError`` naming the file that every other
damaged image gives.
"""

from __future__ import annotations

import io
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Literal

import numpy as np
import pytest

from navkit.mapping.io import read_map

Image = pytest.importorskip("PIL.Image")

_YAML = (
    "image: map.tif\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\n"
    "occupied_thresh: 0.65\nfree_thresh: 0.196\nnegate: 0\n"
)


def _tiff(compression: str | None) -> bytes:
    pixels = (np.arange(48 * 64) % 256).astype(np.uint8).reshape(48, 64)
    out = io.BytesIO()
    if compression is None:
        Image.fromarray(pixels).save(out, format="TIFF")
    else:
        Image.fromarray(pixels).save(out, format="TIFF", compression=compression)
    return out.getvalue()


@pytest.mark.parametrize(
    "damaged",
    [
        pytest.param(lambda: _tiff(None)[:8], id="header-only"),
        pytest.param(lambda: _tiff("tiff_lzw")[:100], id="lzw-cut"),
    ],
)
@pytest.mark.parametrize("action", ["error", "ignore"])
def test_a_damaged_tiff_is_a_value_error_naming_it(
    damaged: Callable[[], bytes], action: Literal["error", "ignore"], tmp_path: Path
) -> None:
    image = tmp_path / "map.tif"
    image.write_bytes(damaged())
    (tmp_path / "map.yaml").write_text(_YAML, encoding="utf-8")
    with warnings.catch_warnings():
        warnings.simplefilter(action)
        with pytest.raises(ValueError, match=r"map\.tif"):
            read_map(tmp_path / "map.yaml")


def test_a_sound_tiff_still_reads(tmp_path: Path) -> None:
    (tmp_path / "map.tif").write_bytes(_tiff("tiff_lzw"))
    (tmp_path / "map.yaml").write_text(_YAML, encoding="utf-8")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        grid = read_map(tmp_path / "map.yaml")
    assert grid.shape == (48, 64)
