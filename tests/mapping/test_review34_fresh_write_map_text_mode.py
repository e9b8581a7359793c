"""``write_map``/``OccupancyGrid.save`` with ``mode`` a str subclass (``np.str_``).

A fresh-eyes review of review 33's "text checked as stored" fixes, looking for
the same pattern elsewhere: ``mode=np.str_("trinary")`` (a mode read from a
NumPy array of options) passed the checks, went into the YAML as it was, and
PyYAML's safe dumper raised its own ``RepresenterError`` (no ``ValueError`` nor
``TypeError``). It is now checked and written as the plain str; a subclass
whose own ``==`` is case-blind is refused for ``"TRINARY"``, as the plain text
it would write.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from case_blind import CaseBlind
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map, write_map


def _grid() -> OccupancyGrid:
    occupied = np.zeros((3, 4), dtype=bool)
    occupied[1, 2] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.25, origin=(1.0, -2.0, 0.0))


@pytest.mark.parametrize("mode", ["trinary", "scale"])
def test_a_numpy_text_mode_writes_the_map_a_plain_one_writes(tmp_path: Path, mode: str) -> None:
    pytest.importorskip("PIL")
    grid = _grid()
    for folder in ("plain", "numpy", "saved"):
        (tmp_path / folder).mkdir()
    plain = write_map(grid, tmp_path / "plain" / "map.yaml", mode=mode)
    numpy = write_map(grid, tmp_path / "numpy" / "map.yaml", mode=np.str_(mode))
    assert numpy.name == plain.name
    assert numpy.read_bytes() == plain.read_bytes()
    yaml_text = (tmp_path / "numpy" / "map.yaml").read_text()
    assert yaml_text == (tmp_path / "plain" / "map.yaml").read_text()
    assert f"mode: {mode}\n" in yaml_text
    back = read_map(tmp_path / "numpy" / "map.yaml")
    assert back.occupied().tolist() == grid.occupied().tolist()
    saved = grid.save(tmp_path / "saved" / "map.yaml", mode=np.str_(mode))
    assert saved.read_bytes() == plain.read_bytes()


def test_a_case_blind_mode_is_checked_as_the_text_it_would_write(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="mode must be 'trinary' or 'scale', got 'TRINARY'"):
        write_map(_grid(), tmp_path / "map.yaml", mode=CaseBlind("TRINARY"))
    assert list(tmp_path.iterdir()) == []  # nothing written
    write_map(_grid(), tmp_path / "map.yaml", mode=CaseBlind("trinary"))
    assert "mode: trinary\n" in (tmp_path / "map.yaml").read_text()


def test_a_mode_that_is_no_text_is_still_a_type_error(tmp_path: Path) -> None:
    with pytest.raises(TypeError, match="mode must be a str, got bytes"):
        write_map(_grid(), tmp_path / "map.yaml", mode=b"trinary")  # type: ignore[arg-type]
    assert list(tmp_path.iterdir()) == []
