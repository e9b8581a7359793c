"""``navkit plan`` takes the map YAMLs ``read_map`` takes (review 20, FOUND item 6).

Maps saved on Windows may be UTF-16 or UTF-32 text with a byte-order mark
(PowerShell 5's ``>`` writes UTF-16); ``read_map`` reads them, but ``navkit
plan --plot FILE`` with an existing FILE read the YAML again as UTF-8 only,
to refuse a ``--plot`` naming the map's image, and failed with "'utf-8' codec
can't decode byte 0xff". It now reads the YAML's bytes with the YAML library
(which detects UTF-8 and UTF-16); where it still cannot tell (UTF-32) it
refused an existing ``--plot`` in one clear line instead of guessing. Since
review 54 (FOUND8) it asks ``navkit.mapping.io.map_image_path`` (read_map's
own reading), so a UTF-32 or tabbed map's existing ``--plot`` is replaced and
its image still refused.
"""

from __future__ import annotations

import codecs
from pathlib import Path

import numpy as np
import pytest

from navkit.cli import main
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map

GRID = OccupancyGrid.from_occupancy(np.zeros((20, 40), dtype=bool), resolution=0.1)
PLAN = ["--start", "0.5,0.5", "--goal", "3.5,1.5", "--quiet"]
ENCODINGS = {
    "utf-8-sig": codecs.BOM_UTF8,
    "utf-16-le": codecs.BOM_UTF16_LE,
    "utf-16-be": codecs.BOM_UTF16_BE,
    "utf-32-le": codecs.BOM_UTF32_LE,
    "utf-32-be": codecs.BOM_UTF32_BE,
}


def _map(folder: Path, encoding: str, image_png: bool = False) -> tuple[Path, Path]:
    """A map whose YAML is in ``encoding`` (with its byte-order mark); its image."""
    yaml_path = folder / "map.yaml"
    image = GRID.save(yaml_path)
    if image_png:
        image_module = pytest.importorskip("PIL.Image")
        png = folder / "map.png"
        image_module.open(image).save(png)
        yaml_path.write_text(yaml_path.read_text().replace(image.name, png.name))
        image = png
    text = yaml_path.read_text()
    bom = ENCODINGS[encoding]
    codec = encoding.replace("-sig", "")
    yaml_path.write_bytes(bom + text.encode(codec))
    return yaml_path, image


def _error(capsys: pytest.CaptureFixture[str]) -> str:
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("navkit: error: "), lines
    return lines[0]


@pytest.mark.parametrize("encoding", ["utf-8-sig", "utf-16-le", "utf-16-be"])
def test_an_existing_plot_is_replaced_for_any_yaml_the_reader_reads(
    tmp_path: Path, encoding: str
) -> None:
    yaml_path, _ = _map(tmp_path, encoding)
    assert read_map(yaml_path).shape == GRID.shape  # the library reads it
    picture = tmp_path / "plan.png"
    picture.write_bytes(b"an old picture")
    assert main(["plan", str(yaml_path), *PLAN, "--plot", str(picture)]) == 0
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("encoding", ["utf-16-le", "utf-16-be"])
def test_plot_over_the_image_of_a_utf16_map_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], encoding: str
) -> None:
    yaml_path, image = _map(tmp_path, encoding, image_png=True)
    before = image.read_bytes()
    assert main(["plan", str(yaml_path), *PLAN, "--plot", str(image)]) == 1
    line = _error(capsys)
    assert "--plot" in line and "map's image" in line
    assert image.read_bytes() == before


@pytest.mark.parametrize("encoding", ["utf-32-le", "utf-32-be"])
def test_utf32_maps_plan_and_an_existing_plot_is_replaced_but_not_their_image(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], encoding: str
) -> None:
    yaml_path, image = _map(tmp_path, encoding, image_png=True)
    assert main(["plan", str(yaml_path), *PLAN, "--plot", str(tmp_path / "new.png")]) == 0
    picture = tmp_path / "plan.png"
    picture.write_bytes(b"an old picture")
    assert main(["plan", str(yaml_path), *PLAN, "--plot", str(picture)]) == 0
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    before = image.read_bytes()
    capsys.readouterr()
    assert main(["plan", str(yaml_path), *PLAN, "--plot", str(image)]) == 1
    line = _error(capsys)
    assert "--plot" in line and "map's image" in line and "codec" not in line
    assert image.read_bytes() == before


def test_plot_over_the_yaml_is_still_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    yaml_path, _ = _map(tmp_path, "utf-16-le")
    before = yaml_path.read_bytes()
    # check_output refuses a non-.png name first: a .png named YAML then.
    png_yaml = tmp_path / "yaml.png"
    yaml_path.rename(png_yaml)
    assert main(["plan", str(png_yaml), *PLAN, "--plot", str(png_yaml)]) == 1
    assert "--plot" in _error(capsys)
    assert png_yaml.read_bytes() == before


def test_a_tabbed_map_plans_and_an_existing_plot_is_replaced(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # Tabs between tokens, which map_server's yaml-cpp and read_map take and PyYAML
    # refuses (review 21): an existing plot was refused until review 54.
    yaml_path, image = _map(tmp_path, "utf-8-sig")
    text = yaml_path.read_bytes()[len(codecs.BOM_UTF8) :].decode()
    yaml_path.write_text(text.replace("resolution: ", "resolution:\t"))
    assert read_map(yaml_path).resolution == GRID.resolution
    assert main(["plan", str(yaml_path), *PLAN, "--plot", str(tmp_path / "new.png")]) == 0
    picture = tmp_path / "plan.png"
    picture.write_bytes(b"an old picture")
    assert main(["plan", str(yaml_path), *PLAN, "--plot", str(picture)]) == 0
    assert picture.read_bytes() != b"an old picture"
    before = image.read_bytes()
    capsys.readouterr()
    assert main(["plan", str(yaml_path), *PLAN, "--json", str(image)]) == 1
    line = _error(capsys)
    assert "--json" in line and "map's image" in line
    assert image.read_bytes() == before
