"""Map and log readers say "1 field", "1 value", "1 byte" (review 31, FNF).

Before: "only 1 fields", "1 fields after the beam count 3", "msg.data has 1
values", "PGM raster truncated: 1 bytes for 2 x 1 pixels (2 bytes needed)" and
"(1 bytes needed)". Written by the shared ``counted`` now. Checked against the
source before the fix: each case failed there.
"""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import pytest

from navkit.mapping.io import grid_from_msg, read_carmen, read_map


@pytest.mark.parametrize(
    ("line", "words"),
    [
        ("ROBOTLASER1 0", "only 1 field"),
        ("ROBOTLASER1 0 -1.5 3.1 0.01 10 0.1 0 3 1", "1 field after the beam count 3"),
    ],
)
def test_carmen_one_field(tmp_path: Path, line: str, words: str) -> None:
    log = tmp_path / "one.log"
    log.write_text(line + "\n")
    with pytest.raises(ValueError) as info:
        read_carmen(log)
    assert str(info.value).endswith(f"malformed ROBOTLASER1 line: {words}")


def test_grid_message_of_one_value() -> None:
    origin = SimpleNamespace(position=SimpleNamespace(x=0.0, y=0.0, z=0.0),
                             orientation=SimpleNamespace(x=0.0, y=0.0, z=0.0, w=1.0))  # fmt: skip
    info = SimpleNamespace(width=2, height=2, resolution=0.1, origin=origin)
    with pytest.raises(ValueError) as caught:
        grid_from_msg(SimpleNamespace(info=info, data=[0]))
    assert str(caught.value) == "msg.data has 1 value, expected width*height = 4"


@pytest.mark.parametrize(
    ("width", "raster", "words"),
    [
        (1, b"", "0 bytes for 1 x 1 pixels (1 byte needed)"),
        (2, b"\x00", "1 byte for 2 x 1 pixels (2 bytes needed)"),
    ],
)
def test_pgm_one_byte(tmp_path: Path, width: int, raster: bytes, words: str) -> None:
    (tmp_path / "m.pgm").write_bytes(b"P5\n%d 1\n255\n" % width + raster)
    yaml = "image: m.pgm\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
    (tmp_path / "m.yaml").write_text(yaml + "occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    with pytest.raises(ValueError) as info:
        read_map(tmp_path / "m.yaml")
    assert str(info.value).endswith(f"PGM raster truncated: {words}")
