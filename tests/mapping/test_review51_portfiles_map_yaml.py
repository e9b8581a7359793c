"""Review 51 (PORTFILES): map YAMLs hand-edited elsewhere, crafted from a real map_server map.

A line of blanks only (or blanks before a comment) with a tab in it is a blank
or comment line in YAML 1.2 (``l-comment``: its tabs are separation, not
indentation) and map_server's yaml-cpp eats such tabs; PyYAML refused the file
("found character '\\t' that cannot start any token"), so navkit refused a map
map_server loads. A tab indenting a key stays refused, as YAML and yaml-cpp refuse it.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import read_map

_MAP = Path("ros-map-server-maps") / "turtlebot3_world"


def _copy(shared_data: Path, tmp_path: Path) -> str:
    shutil.copy(shared_data / _MAP / "map.pgm", tmp_path / "map.pgm")
    return (shared_data / _MAP / "map.yaml").read_text(encoding="utf-8")


def _same_map(path: Path, shared_data: Path) -> None:
    ref = read_map(shared_data / _MAP / "map.yaml")
    got = read_map(path)
    assert got.origin == ref.origin
    assert got.resolution == ref.resolution
    assert (got.occupied_thresh, got.free_thresh) == (ref.occupied_thresh, ref.free_thresh)
    assert np.array_equal(got.occupied(), ref.occupied())
    assert np.array_equal(got.free(), ref.free())


@pytest.mark.parametrize(
    ("label", "edit"),
    [
        ("tab-only line between keys", lambda t: t.replace("negate", "\t\nnegate")),
        ("spaces and tabs line", lambda t: t.replace("negate", " \t  \t\nnegate")),
        ("tab before a whole-line comment", lambda t: t.replace("negate", "\t# edited\nnegate")),
        ("tab-only last line", lambda t: t.rstrip("\n") + "\n\t"),
        ("tab-only line, CRLF", lambda t: t.replace("negate", "\t\nnegate").replace("\n", "\r\n")),
        ("tab-only line, CR", lambda t: t.replace("negate", "\t\nnegate").replace("\n", "\r")),
    ],
)
def test_tabs_on_blank_and_comment_lines_are_blanks(
    shared_data: Path, tmp_path: Path, label: str, edit: object
) -> None:
    text = _copy(shared_data, tmp_path)
    assert callable(edit)
    (tmp_path / "map.yaml").write_bytes(edit(text).encode("utf-8"))
    _same_map(tmp_path / "map.yaml", shared_data)


def test_a_tab_indenting_a_key_stays_refused(shared_data: Path, tmp_path: Path) -> None:
    text = _copy(shared_data, tmp_path)
    (tmp_path / "map.yaml").write_text(text.replace("negate", "\tnegate"), encoding="utf-8")
    with pytest.raises(ValueError, match=r"map\.yaml:\d+: expected 'key: value' lines"):
        read_map(tmp_path / "map.yaml")
