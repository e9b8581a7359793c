"""Map YAMLs with tabs between tokens read as map_server reads them (review 20).

YAML 1.2 and yaml-cpp (map_server's reader) take a tab as a blank between
tokens; PyYAML refused ``resolution:<TAB>0.05``, a tab inside a flow sequence
or before a comment ("found character '\\t' that cannot start any token"), so a
hand-edited map that ROS loads was refused by navkit. A tab inside a quoted
scalar is the scalar's own; a tab in an indent stays an error.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping.io import read_map

_LINES = [
    ("image", "m.pgm"),
    ("resolution", "0.05"),
    ("origin", "[1.5, -2.0, 0.0]"),
    ("negate", "0"),
    ("occupied_thresh", "0.65"),
    ("free_thresh", "0.196"),
]


def _write(folder: Path, text: str) -> Path:
    (folder / "m.pgm").write_bytes(b"P5 2 1 255 \x00\xff")
    path = folder / "m.yaml"
    path.write_text(text, encoding="utf-8")
    return path


@settings(max_examples=25, deadline=None)
@given(st.lists(st.sampled_from([" ", "\t"]), min_size=len(_LINES) * 3, max_size=len(_LINES) * 3))
def test_tabs_between_tokens_read_as_spaces(tmp_path_factory: pytest.TempPathFactory,
                                            blanks: list[str]) -> None:  # fmt: skip
    folder = tmp_path_factory.mktemp("tabs")
    lines = []
    for k, (key, value) in enumerate(_LINES):
        after_colon, inside, before_comment = blanks[3 * k : 3 * k + 3]
        value = value.replace(", ", "," + inside)
        lines.append(f"{key}:{after_colon}{value}{before_comment}# note\t{k}")
    tabbed = read_map(_write(folder, "\n".join(lines) + "\n"))
    plain = read_map(_write(folder, "".join(f"{k}: {v}\n" for k, v in _LINES)))
    assert tabbed.resolution == plain.resolution == 0.05
    assert tabbed.origin == plain.origin
    np.testing.assert_array_equal(tabbed.logodds, plain.logodds)


def test_a_tab_in_a_quoted_image_name_is_the_names_own(tmp_path: Path) -> None:
    (tmp_path / "a\tb.pgm").write_bytes(b"P5 1 1 255 \xff")
    text = "".join(f"{k}:\t{v}\n" for k, v in _LINES if k != "image")
    path = tmp_path / "m.yaml"
    path.write_text('image:\t"a\\tb.pgm"\n' + text, encoding="utf-8")
    assert read_map(path).shape == (1, 1)


def test_a_tab_in_an_indent_is_still_refused(tmp_path: Path) -> None:
    text = "".join(f"{k}: {v}\n" for k, v in _LINES).replace("negate", "\tnegate")
    with pytest.raises(ValueError, match=r"m\.yaml:4: expected 'key: value' lines"):
        read_map(_write(tmp_path, text))
