"""`navkit plan --json` refuses a map image named like a YAML 1.1 boolean or date (review 53).

MUTANT33: 649d386's check reads the map YAML with a loader that keeps every
scalar's text. Its test covered numbers only; mutants keeping PyYAML's
booleans (``on`` read as True) or timestamps (a time of day, which PyYAML
makes a datetime printed otherwise) passed it. At 649d386 read_map
refused such image names itself, so no plan was written; since c1db3bd it
reads ``image: on`` as the file ``on``, as map_server does, and those mutants
let ``--json on`` replace the map's image with the plan.
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


@pytest.mark.parametrize("name", ["on", "yes", "Off", "2001-12-14", "2001-12-14t21:59:43.10-05:00"])
def test_a_json_naming_a_word_named_map_image_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], name: str
) -> None:
    yaml_path = tmp_path / "map.yaml"
    pgm = GRID.save(yaml_path)
    image = tmp_path / name
    pgm.rename(image)
    text = yaml_path.read_text(encoding="utf-8").replace(f"image: {pgm.name}", f"image: {name}")
    yaml_path.write_text(text, encoding="utf-8")
    assert f"image: {name}\n" in text
    assert np.array_equal(read_map(yaml_path).occupied(), GRID.occupied())
    before = image.read_bytes()
    capsys.readouterr()
    assert main(["plan", str(yaml_path), *PLAN, "--json", str(image)]) == 1
    err = capsys.readouterr().err
    assert "--json" in err and "is the map's image" in err, err
    assert image.read_bytes() == before
