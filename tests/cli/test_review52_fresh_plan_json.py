"""Review 52 (FRESH): `navkit plan --json` never overwrites a map image named like a number.

``read_map`` reads ``image: 017`` (and ``1_000``, ``0x1F``, ``0b101``,
``1:20``: numbers in YAML 1.1 only) as the file of that name, as map_server's
yaml-cpp does; the command's check that an output does not name the map's
image read the YAML with PyYAML's safe loader, which made those numbers
(``017`` is 15), so ``--json 017`` replaced the map's image with the plan.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navkit.cli import main
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map

_WALL = np.zeros((20, 40), dtype=bool)
_WALL[5:15, 20] = True
GRID = OccupancyGrid.from_occupancy(_WALL, resolution=0.1)
PLAN = ["--start", "0.5,1.5", "--goal", "3.5,0.5", "--quiet"]


def _numbered_map(folder: Path, name: str) -> Path:
    """A map whose YAML names its PGM image ``name``, written plain; the image's path."""
    yaml_path = folder / "map.yaml"
    pgm = GRID.save(yaml_path)
    image = folder / name
    pgm.rename(image)
    text = yaml_path.read_text(encoding="utf-8")
    yaml_path.write_text(text.replace(f"image: {pgm.name}", f"image: {name}"), encoding="utf-8")
    assert f"image: {name}\n" in yaml_path.read_text(encoding="utf-8")
    return image


@pytest.mark.parametrize("name", ["017", "1_000", "0x1F", "0b101", "1:20", "1_0.5"])
def test_a_json_naming_a_number_named_map_image_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], name: str
) -> None:
    image = _numbered_map(tmp_path, name)
    yaml_path = tmp_path / "map.yaml"
    assert np.array_equal(read_map(yaml_path).occupied(), GRID.occupied())
    before = image.read_bytes()
    capsys.readouterr()
    assert main(["plan", str(yaml_path), *PLAN, "--json", str(image)]) == 1
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("navkit: error: "), lines
    assert "--json" in lines[0] and "is the map's image" in lines[0]
    assert image.read_bytes() == before
    # Another existing file, named as the number PyYAML reads, is still replaced.
    other = tmp_path / "15"
    other.write_text("old")
    assert main(["plan", str(yaml_path), *PLAN, "--json", str(other)]) == 0
    assert other.read_text().startswith("{")
