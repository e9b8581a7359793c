"""Review 53 (FOUND5): the missing-image hint names only spellings case-insensitive systems match.

``read_map``'s error for a missing image names a file beside it spelt the
same but for case or normalisation (found on Windows or macOS, not on Linux).
It compared names by ``str.casefold``, Unicode's *full* case folding, by which
``straße.pgm`` is ``STRASSE.pgm``; NTFS's upcase table and APFS's folding go
character by character (simple case folding keeps a name's length), and hold
those as two files. Names are compared by simple case folding now: ``ẞ``
(U+1E9E) still folds to ``ß``, ``ss`` does not.
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
        ("straße.pgm", "STRASSE.pgm"),
        ("STRASSE.pgm", "straße.pgm"),
        ("strasse.pgm", "STRAẞE.pgm"),
        ("ﬁle.pgm", "FILE.pgm"),  # the ligature U+FB01 folds fully to "fi"
        ("\u0149.pgm", "\u02bcN.pgm"),  # U+0149 folds fully to U+02BC n, simply to itself
    ],
)
def test_a_full_folding_only_match_is_no_hint(tmp_path: Path, named: str, on_disk: str) -> None:
    message = _missing(tmp_path, named, on_disk)
    assert message.endswith("does not exist"), message
    assert "its folder holds" not in message


@pytest.mark.parametrize(
    ("named", "on_disk"),
    [
        ("map.pgm", "Map.PGM"),
        ("straße.pgm", "STRAẞE.pgm"),  # U+1E9E folds simply to ß
        ("ᾀ.pgm", "ᾈ.PGM"),  # Greek with prosgegrammeni: a simple folding too
        ("Χάρτης.pgm", "χάρτης.pgm"),
    ],
)
def test_a_simple_folding_match_is_named(tmp_path: Path, named: str, on_disk: str) -> None:
    message = _missing(tmp_path, named, on_disk)
    assert f"its folder holds {on_disk!r}, which differs in letter case" in message
