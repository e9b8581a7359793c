"""A tab inside a map YAML's value is refused even where a tab elsewhere moves structure.

Review 21 refused a tab inside a value by loading a tabbed YAML twice, its
tabs between tokens as one space and as two, and comparing. Where the second
load failed (a tab after a sequence's ``-`` whose width moves the lines that
follow it) the first was taken unchecked: ``image: my<TAB>map.pgm`` in such a
file was again read as ``my map.pgm``, another file (review 22, fresh eyes).
The first load is now checked by where its tabs lie: inside a plain or block
scalar, the file is refused with the key named.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping.io import read_map
from navkit.mapping.io._map_files import _load_yaml

_REST = (
    "resolution:\t0.05\norigin: [0.0,\t0.0, 0.0]\nnegate: 0\n"
    "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
)
# A key map_server ignores whose sequence entry follows its "-" by a tab: read with
# the tab as one space the mapping's lines line up, as two they do not.
_MOVED = "extra:\n-\ta: 1\n  b: 2\n"


def _image(path: Path, value: int) -> None:
    path.write_bytes(b"P5 1 1 255 " + bytes([value]))


def test_the_structure_loads_with_one_blank_only() -> None:
    # What makes the case: the two-blank load fails, so it cannot be compared.
    assert yaml.safe_load(_MOVED.replace("\t", " ")) == {"extra": [{"a": 1, "b": 2}]}
    with pytest.raises(yaml.YAMLError):
        yaml.safe_load(_MOVED.replace("\t", "  "))


@pytest.mark.parametrize("order", ["before", "after"])
def test_a_tab_inside_the_image_name_is_refused_beside_moved_structure(
    tmp_path: Path, order: str
) -> None:
    _image(tmp_path / "my\tmap.pgm", 0)  # the file yaml-cpp would read: occupied
    _image(tmp_path / "my map.pgm", 255)  # another map: free (was read)
    image = "image:\tmy\tmap.pgm\n"
    text = image + _REST + _MOVED if order == "after" else _MOVED + image + _REST
    yaml_path = tmp_path / "m.yaml"
    yaml_path.write_text(text, encoding="utf-8")
    with pytest.raises(ValueError, match=r"m\.yaml: a tab inside the value of 'image'.*quote it"):
        read_map(yaml_path)


def test_moved_structure_with_tabs_only_between_tokens_still_reads(tmp_path: Path) -> None:
    _image(tmp_path / "my\tmap.pgm", 0)
    yaml_path = tmp_path / "m.yaml"
    text = "image:\t'my\tmap.pgm'\t# a\tnote\n" + _REST + _MOVED + "q: [1,\t'x\ty']\n"
    yaml_path.write_text(text.replace("\n", "\r\n"), encoding="utf-8", newline="")
    grid = read_map(yaml_path)
    assert grid.resolution == 0.05
    np.testing.assert_array_equal(grid.occupied(), [[True]])


@pytest.mark.parametrize(
    ("extra", "match"),
    [
        ("my\tkey: 1\n", r"a tab inside a key"),
        ("note: |\n  a\tb\n", r"a tab inside the value of 'note'"),
        ("deep: {x: [1, a\tb]}\n", r"a tab inside the value of 'deep'"),
    ],
)
def test_every_kind_of_tab_inside_is_refused_beside_moved_structure(
    tmp_path: Path, extra: str, match: str
) -> None:
    _image(tmp_path / "m.pgm", 0)
    yaml_path = tmp_path / "m.yaml"
    yaml_path.write_text("image: m.pgm\n" + _REST + _MOVED + extra, encoding="utf-8")
    with pytest.raises(ValueError, match=match):
        read_map(yaml_path)


def test_nested_aliases_beside_moved_structure_read(tmp_path: Path) -> None:
    # 2**60 leaves once expanded: the check visits each shared node once.
    _image(tmp_path / "m.pgm", 0)
    laughs = "n0: &a0 [0.5, .nan]\n" + "".join(
        f"n{k}: &a{k} [*a{k - 1}, *a{k - 1}]\n" for k in range(1, 61)
    )
    yaml_path = tmp_path / "m.yaml"
    yaml_path.write_text("image:\tm.pgm\n" + laughs + _REST + _MOVED, encoding="utf-8")
    assert read_map(yaml_path).resolution == 0.05


@settings(max_examples=200, deadline=None)
@given(
    st.text(alphabet="ab_ \t", min_size=1, max_size=12).filter(lambda v: v.strip(" \t") == v),
    st.sampled_from([" ", "\t", " \t"]),
    st.sampled_from(["", "\t", " ", "\t# c", " #\tc"]),
    st.booleans(),
)
def test_a_plain_value_is_read_as_written_or_refused(
    value: str, blank: str, tail: str, first: bool
) -> None:
    # As review 21's property, with the moved structure in the file: the value as
    # written (yaml-cpp's reading, tabs included) or a refusal, never another value.
    line = f"key:{blank}{value}{tail}\n"
    text = line + _MOVED if first else _MOVED + line
    try:
        doc = _load_yaml(text, Path("m.yaml"))
    except ValueError as exc:
        assert "\t" in value
        assert "a tab inside the value of 'key'" in str(exc)
        return
    assert doc["key"] == value
    assert doc["extra"] == [{"a": 1, "b": 2}]
