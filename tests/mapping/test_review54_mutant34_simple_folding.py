"""Review 54 (MUTANT34): simple case folding is folding, not lower case.

Review 53 compares image names by Unicode's simple case folding (what NTFS and
APFS match). Its tests' letters fold as they lower-case, so folding a
character by ``str.lower`` where ``str.casefold`` gives one character passed
them. Final sigma, the micro sign, and the long s fold to another
letter than their lower case (CaseFolding.txt's C entries):
σ and ς are one name on a case-insensitive file system.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map

GRID = OccupancyGrid.from_occupancy(np.eye(5, dtype=bool), resolution=0.1)


def _missing(folder: Path, named: str, on_disk: str) -> str:
    """The error of a map YAML naming ``named`` beside the image ``on_disk``."""
    yaml_path = folder / "map.yaml"
    pgm = GRID.save(yaml_path)
    try:
        pgm.rename(folder / on_disk)
    except OSError:
        pytest.skip("the file system cannot hold that name")
    if (folder / named).exists():
        pytest.skip("a file system that matches names regardless of case")
    text = yaml_path.read_text(encoding="utf-8").replace(f"image: {pgm.name}", f"image: {named}")
    yaml_path.write_text(text, encoding="utf-8")
    with pytest.raises(FileNotFoundError) as info:
        read_map(yaml_path)
    return str(info.value)


@pytest.mark.parametrize(
    ("named", "on_disk"),
    [
        ("χάρτης.pgm", "χάρτησ.pgm"),  # final sigma U+03C2 folds to σ, its lower case is itself
        ("\u00b5m.pgm", "\u03bcm.pgm"),  # micro sign folds to Greek mu
        ("\u017fite.pgm", "site.pgm"),  # long s folds to s
    ],
)
def test_letters_folding_unlike_their_lower_case_are_named(
    tmp_path: Path, named: str, on_disk: str
) -> None:
    assert named.lower() != on_disk.lower() and named.casefold() == on_disk.casefold()
    message = _missing(tmp_path, named, on_disk)
    assert f"its folder holds {on_disk!r}, which differs in letter case" in message
