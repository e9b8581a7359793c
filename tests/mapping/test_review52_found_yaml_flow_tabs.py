"""A map YAML's flow list continued on a line led by a tab (review 52, FOUND4).

Inside ``[...]`` a line's leading blanks are separation, not indentation:
YAML 1.2 (ruamel.yaml) and map_server's yaml-cpp read ``origin: [1.5,``
continued on a line ``<TAB>-2.0, 0.0]``; PyYAML refused it ("found character
'\\t' that cannot start any token"), and so did navkit, naming the line. Review
51 kept the refusal, taking map_server to refuse too; yaml-cpp eats a tab
wherever it skips blanks. A tab indenting a key or a block value (outside
every flow collection) stays refused, as YAML and PyYAML refuse it.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import read_map

HEAD = "image: m.pgm\nresolution: 0.05\n"
TAIL = "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
PLAIN = HEAD + "origin: [1.5, -2.0, 0.25]\n" + TAIL


def _write(folder: Path, text: str, name: str = "m.yaml") -> Path:
    (folder / "m.pgm").write_bytes(b"P5 2 1 255 \x00\xff")
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize(
    "origin",
    [
        "origin: [1.5,\n\t-2.0, 0.25]\n",  # a tab alone (yaml-cpp and ruamel.yaml read it)
        "origin: [1.5,\n \t-2.0, 0.25]\n",  # a space, then a tab: YAML 1.2 to the letter
        "origin: [1.5,\n  -2.0,\n\t\t0.25]\n",
        "origin: [\n\t1.5,\t-2.0,\n\t0.25\n\t]\n",
        "origin: [1.5, # x\n\t-2.0, # y\n\t0.25]\n",  # comments between
        "origin: [1.5, -2.0, 0.25]\nmode: {a: [1,\n\t2],\n\tb: 3}\n",  # nested flows
    ],
)
def test_a_flow_list_continued_on_a_tab_led_line_reads_as_with_spaces(
    tmp_path: Path, origin: str
) -> None:
    # (mode is not a mapping in a map YAML: the nested flows' case checks only that
    # the tabs are read as blanks, to a refusal of mode itself.)
    text = HEAD + origin + TAIL
    if "mode:" in origin:
        with pytest.raises(ValueError, match=r"mode"):
            read_map(_write(tmp_path, text))
        return
    tabbed = read_map(_write(tmp_path, text))
    plain = read_map(_write(tmp_path, PLAIN, "plain.yaml"))
    assert tabbed.origin == plain.origin and tabbed.origin.x == 1.5
    assert tabbed.origin.y == -2.0 and tabbed.origin.theta == 0.25
    np.testing.assert_array_equal(tabbed.logodds, plain.logodds)


def test_a_quoted_image_name_beside_a_tab_led_flow_line_is_kept(tmp_path: Path) -> None:
    (tmp_path / "a\tb.pgm").write_bytes(b"P5 1 1 255 \xff")
    text = 'image: "a\\tb.pgm"\nresolution: 0.05\norigin: [1.5,\n\t-2.0, 0.25]\n' + TAIL
    grid = read_map(_write(tmp_path, text))
    assert grid.shape == (1, 1) and grid.origin.y == -2.0


@pytest.mark.parametrize(
    ("text", "line"),
    [
        (HEAD + "origin:\n\t[1.5, -2.0, 0.25]\n" + TAIL, 4),  # a block value indented by a tab
        (HEAD + "origin: [1.5,\n\t-2.0, 0.25]\n\tnegate: 0\n" + TAIL[10:], 5),  # a key's
    ],
)
def test_a_tab_indent_outside_every_flow_collection_stays_refused(
    tmp_path: Path, text: str, line: int
) -> None:
    with pytest.raises(ValueError, match=rf"m\.yaml:{line}: expected 'key: value' lines"):
        read_map(_write(tmp_path, text))
