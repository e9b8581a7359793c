"""read_map's tabbed blank lines and missing-image hints at their edges (review 52, MUTANT32).

Review 51 (PORTFILES) reads a map YAML whose blank or comment-only lines hold
tabs, as map_server does: only such lines, from their start. A mutant that
also spaced the blanks before any ``#`` (its pattern unanchored) passed every
test; it turned a tab inside a quoted image name, before a ``#``, into a space.
The hint for an absolute image path names a *file* of its name beside the
YAML: a mutant naming any entry (a folder too) passed. Where the text cannot
even be scanned (an unclosed quote), a tab indenting a key is refused naming
its line, as review 52 (FOUND4) says: a mutant spacing every line's leading
tabs then passed, and named line 1 for another problem. FOUND4's reading of
``negate`` as yaml-cpp's C integer was tested inside int's range and without
a sign kept as text: mutants refusing ``-2147483648`` and a ``+`` passed.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map

_WALLS = np.zeros((12, 16), dtype=bool)
_WALLS[3:9, 7] = True
GRID = OccupancyGrid.from_occupancy(_WALLS, resolution=0.1)


def _map(folder: Path, image_line: str, name: str | None) -> Path:
    """A map whose YAML's image line is ``image_line``, its image renamed ``name`` (or removed)."""
    yaml_path = folder / "map.yaml"
    pgm = GRID.save(yaml_path)
    text = yaml_path.read_text(encoding="utf-8")
    if name is None:
        pgm.unlink()
    else:
        pgm.rename(folder / name)
    yaml_path.write_text(text.replace(f"image: {pgm.name}", image_line), encoding="utf-8")
    return yaml_path


@pytest.mark.parametrize("blank", ["\t\n", " \t \n", "\t# edited\n"])
def test_a_tab_before_a_hash_inside_a_quoted_image_name_is_kept(tmp_path: Path, blank: str) -> None:
    name = "map\t#1.pgm"
    yaml_path = _map(tmp_path, 'image: "map\t#1.pgm"', name)
    # A tabbed blank line: the file is read the tolerant way, the image name as written.
    text = yaml_path.read_text(encoding="utf-8")
    yaml_path.write_text(text.replace("negate", blank + "negate"), encoding="utf-8")
    grid = read_map(yaml_path)
    assert np.array_equal(grid.occupied(), GRID.occupied())


def test_a_folder_beside_the_yaml_is_not_named_for_an_absolute_image(tmp_path: Path) -> None:
    image = "/nonexistent-navkit-test/maps/map.pgm"
    if Path(image).exists():
        pytest.skip(f"{image} exists on this machine")
    yaml_path = _map(tmp_path, f"image: {image}", None)
    (tmp_path / "map.pgm").mkdir()
    with pytest.raises(FileNotFoundError) as info:
        read_map(yaml_path)
    message = str(info.value)
    assert "(an absolute path: give the image's path relative to the YAML)" in message
    assert "lies beside" not in message
    # A file of that name is named.
    (tmp_path / "map.pgm").rmdir()
    (tmp_path / "map.pgm").write_bytes(b"P5\n1 1\n255\n\x00")
    with pytest.raises(FileNotFoundError, match=re.escape("'map.pgm' lies beside the YAML")):
        read_map(yaml_path)


def test_a_tab_indented_key_of_a_yaml_that_cannot_be_scanned_is_named(tmp_path: Path) -> None:
    GRID.save(tmp_path / "map.yaml")
    text = 'image: map.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n\tnegate: 0\nmode: "trinary\n'
    tail = "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
    (tmp_path / "map.yaml").write_text(text + tail, encoding="utf-8")
    with pytest.raises(ValueError, match=r"map\.yaml:4: expected 'key: value' lines \(found "):
        read_map(tmp_path / "map.yaml")


@pytest.mark.parametrize(
    ("negate", "number"),
    [("-2147483648", -(2**31)), ("+010", 8), ("-0x10", -16)],
)
def test_a_negate_at_ints_edge_or_signed_says_what_map_server_reads(
    tmp_path: Path, negate: str, number: int
) -> None:
    yaml_path = _map(tmp_path, "image: map.pgm", "map.pgm")
    text = yaml_path.read_text(encoding="utf-8")
    yaml_path.write_text(re.sub(r"negate: \S+", f"negate: {negate}", text), encoding="utf-8")
    verdict = "negated" if number else "not negated"
    hint = f"(map_server reads it as the integer {number}: {verdict}; write {int(number != 0)})"
    with pytest.raises(ValueError) as caught:
        read_map(yaml_path)
    assert "negate must be 0 or 1" in str(caught.value)
    assert str(caught.value).endswith(hint)
