"""Review 51 (PORTFILES): `navkit plan --plot` never overwrites a map image named the Windows way.

``read_map`` reads ``image: maps\\map.png`` (written on Windows) as
``maps/map.png`` where no file has the backslash in its name; the command's
check that ``--plot`` does not name the map's image looked only for the
backslashed name, so ``--plot maps/map.png`` replaced the map's image with
the picture. Its refusal for YAMLs PyYAML cannot read now names the reasons
read_map takes and PyYAML refuses (Latin-1 bytes, tabs on blank lines); since
review 54 (FOUND8) the command asks mapping.io for the image
(``map_image_path``, read_map's own reading) and such a YAML is no refusal.
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


def _windows_map(folder: Path) -> tuple[Path, Path]:
    """A map whose YAML names its PNG image ``maps\\map.png``; the YAML and the image."""
    image_module = pytest.importorskip("PIL.Image")
    yaml_path = folder / "map.yaml"
    pgm = GRID.save(yaml_path)
    (folder / "maps").mkdir()
    png = folder / "maps" / "map.png"
    image_module.open(pgm).save(png)
    pgm.unlink()
    text = yaml_path.read_text(encoding="utf-8")
    yaml_path.write_text(text.replace(pgm.name, "maps\\map.png"), encoding="utf-8")
    return yaml_path, png


def _error(capsys: pytest.CaptureFixture[str]) -> str:
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("navkit: error: "), lines
    return lines[0]


def test_a_plot_naming_a_windows_named_map_image_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    yaml_path, png = _windows_map(tmp_path)
    assert np.array_equal(read_map(yaml_path).occupied(), GRID.occupied())
    before = png.read_bytes()
    capsys.readouterr()
    assert main(["plan", str(yaml_path), *PLAN, "--plot", str(png)]) == 1
    line = _error(capsys)
    assert "--plot" in line and "is the map's image" in line
    assert png.read_bytes() == before
    # Another existing picture is still replaced.
    other = tmp_path / "plan.png"
    other.write_bytes(b"an old picture")
    assert main(["plan", str(yaml_path), *PLAN, "--plot", str(other)]) == 0
    assert other.read_bytes() != b"an old picture"


@pytest.mark.parametrize(
    "edit",
    [
        lambda t: b"# Karte B\xfcro\n" + t,
        lambda t: t.replace(b"negate", b"\t\nnegate"),
    ],
    ids=["latin-1", "tabs"],
)
def test_an_existing_plot_beside_a_yaml_pyyaml_refuses_is_written(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], edit: object
) -> None:
    # Refused until review 54 ("could not be read"): the command read the YAML
    # with PyYAML, which refuses Latin-1 bytes and tabs on blank lines.
    yaml_path = tmp_path / "map.yaml"
    pgm = GRID.save(yaml_path)
    assert callable(edit)
    yaml_path.write_bytes(edit(yaml_path.read_bytes()))
    assert np.array_equal(read_map(yaml_path).occupied(), GRID.occupied())
    picture = tmp_path / "plan.png"
    picture.write_bytes(b"an old picture")
    assert main(["plan", str(yaml_path), *PLAN, "--plot", str(picture)]) == 0
    assert picture.read_bytes() != b"an old picture"
    # The map's own image is still refused.
    before = pgm.read_bytes()
    capsys.readouterr()
    assert main(["plan", str(yaml_path), *PLAN, "--json", str(pgm)]) == 1
    line = _error(capsys)
    assert "--json" in line and "is the map's image" in line
    assert pgm.read_bytes() == before
