"""A tab inside a map YAML's value is refused, not read as a space (review 21, fresh eyes).

Review 20 read tabs between tokens as blanks (yaml-cpp does; PyYAML refused
them) by turning every tab outside quotes into a space. A tab inside a plain
scalar is the value's own, though: ``image:<TAB>my<TAB>map.pgm`` was read as
``my map.pgm`` and loaded that other file where one existed. Such a value is
now refused with the key named; tabs between tokens still read.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping.io import read_map
from navkit.mapping.io._map_files import _load_yaml

_REST = (
    "resolution:\t0.05\norigin: [0.0,\t0.0, 0.0]\nnegate: 0\n"
    "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
)


def _image(path: Path, value: int) -> None:
    path.write_bytes(b"P5 1 1 255 " + bytes([value]))


def test_a_tab_inside_a_plain_image_name_is_refused_not_read_as_a_space(tmp_path: Path) -> None:
    _image(tmp_path / "my\tmap.pgm", 0)  # the file yaml-cpp would read: occupied
    _image(tmp_path / "my map.pgm", 255)  # another map: free
    yaml_path = tmp_path / "m.yaml"
    yaml_path.write_text("image:\tmy\tmap.pgm\n" + _REST, encoding="utf-8")
    with pytest.raises(ValueError, match=r"m\.yaml: a tab inside the value of 'image'.*quote it"):
        read_map(yaml_path)


def test_a_quoted_image_name_with_a_tab_among_tabs_between_tokens_reads(tmp_path: Path) -> None:
    _image(tmp_path / "my\tmap.pgm", 0)
    _image(tmp_path / "my map.pgm", 255)
    yaml_path = tmp_path / "m.yaml"
    yaml_path.write_text("image:\t'my\tmap.pgm'\t# a note\n" + _REST, encoding="utf-8")
    grid = read_map(yaml_path)
    assert grid.resolution == 0.05
    np.testing.assert_array_equal(grid.occupied(), [[True]])


def test_a_tab_inside_a_block_scalar_value_is_refused(tmp_path: Path) -> None:
    _image(tmp_path / "m.pgm", 255)
    yaml_path = tmp_path / "m.yaml"
    yaml_path.write_text("image: m.pgm\nnote: |\n  a\tb\n" + _REST, encoding="utf-8")
    with pytest.raises(ValueError, match=r"a tab inside the value of 'note'"):
        read_map(yaml_path)


def test_tabs_between_tokens_and_in_comments_still_read(tmp_path: Path) -> None:
    _image(tmp_path / "m.pgm", 0)
    yaml_path = tmp_path / "m.yaml"
    yaml_path.write_text("image:\tm.pgm\t# it's\tthe map\n" + _REST, encoding="utf-8")
    grid = read_map(yaml_path)
    assert grid.resolution == 0.05
    assert grid.origin.x == grid.origin.y == grid.origin.theta == 0.0


def test_a_tab_inside_a_key_is_refused(tmp_path: Path) -> None:
    _image(tmp_path / "m.pgm", 255)
    yaml_path = tmp_path / "m.yaml"
    yaml_path.write_text("image: m.pgm\nmy\tnote: 1\n" + _REST, encoding="utf-8")
    with pytest.raises(ValueError, match=r"m\.yaml: a tab inside a key, which PyYAML cannot read"):
        read_map(yaml_path)


def test_a_tabbed_yaml_of_nested_aliases_reads(tmp_path: Path) -> None:
    # 2**60 leaves once expanded: comparing the two loads by value (== or repr)
    # would never end; each shared node is compared once. The map is the other keys'.
    _image(tmp_path / "m.pgm", 0)
    laughs = "n0: &a0 [0.5, .nan]\n" + "".join(
        f"n{k}: &a{k} [*a{k - 1}, *a{k - 1}]\n" for k in range(1, 61)
    )
    yaml_path = tmp_path / "m.yaml"
    yaml_path.write_text("image:\tm.pgm\n" + laughs + _REST, encoding="utf-8")
    grid = read_map(yaml_path)
    assert grid.resolution == 0.05
    np.testing.assert_array_equal(grid.occupied(), [[True]])


@settings(max_examples=200, deadline=None)
@given(
    st.text(alphabet="ab_ \t", min_size=1, max_size=12).filter(lambda v: v.strip(" \t") == v),
    st.sampled_from([" ", "\t", " \t"]),
    st.sampled_from(["", "\t", " ", "\t# c", " #\tc"]),
)
def test_a_plain_value_is_read_as_written_or_refused(value: str, blank: str, tail: str) -> None:
    # YAML (yaml-cpp, map_server's reader) reads the value as written, its tabs
    # included; navkit reads the same or refuses it, never another value.
    try:
        doc = _load_yaml(f"key:{blank}{value}{tail}\nnext:\t1\n", Path("m.yaml"))
    except ValueError as exc:
        assert "\t" in value
        assert "a tab inside the value of 'key'" in str(exc)
        return
    assert doc == {"key": value, "next": 1}
