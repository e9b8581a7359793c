"""Map YAMLs with tabs: quoted scalars found in linear time (review 20, fresh eyes).

The tab rewrite that lets ``read_map`` take ``resolution:<TAB>0.05`` split each
line on one quoted-scalar pattern, which tried every ``"`` of a line anew up to
the line's end where none closes: a comment of ``"`` followed by ``\\"`` pairs
took time quadratic in its length (7.5 s for a 32 KB YAML, hours for the 1 MiB
a map YAML may have). The rewrite now reads the line once; what it produces is
the same, checked here against the former split as the reference.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping.io import read_map
from navkit.mapping.io._map_files import _untabbed

# The former pattern and split (33e58e0..bc877cf): the meaning kept.
_FORMER = re.compile(r"""("(?:[^"\\\n]|\\.)*"|'(?:[^'\n]|'')*')""")


def _former_untabbed(text: str) -> str:
    lines = []
    for line in text.split("\n"):
        body = line.lstrip(" \t")
        parts = _FORMER.split(body)
        spaced = "".join(p if i % 2 else p.replace("\t", " ") for i, p in enumerate(parts))
        lines.append(line[: len(line) - len(body)] + spaced)
    return "\n".join(lines)


@settings(max_examples=300, deadline=None)
@given(st.text(alphabet="\"'\\\t a#:\r\n", max_size=60))
def test_the_rewrite_is_the_former_one(text: str) -> None:
    assert _untabbed(text) == _former_untabbed(text)


@pytest.mark.parametrize(
    ("line", "expected"),
    [
        ('a:\t"x\ty"\t# c', 'a: "x\ty" # c'),
        ('a:\t"x\\"\ty"', 'a: "x\\"\ty"'),  # an escaped quote does not close
        ("a:\t'x''\ty'\t", "a: 'x''\ty' "),  # a doubled quote does not close
        ("#\t\"\\\"\t'p\tq'\tr", "# \"\\\" 'p\tq' r"),  # unclosed ": later 'scalars' count
        ('#\t"\t\\', '# " \\'),  # unclosed, ending in a backslash
        ("\t\tkey:\tv", "\t\tkey: v"),  # the indent stays
    ],
)
def test_tabs_outside_quotes_only(line: str, expected: str) -> None:
    assert _untabbed(line) == expected == _former_untabbed(line)


@pytest.mark.parametrize("unit", ['\\"', '"\\'])
def test_a_mebibyte_of_unclosed_quotes_reads(tmp_path: Path, unit: str) -> None:
    # The former split took hours on each of these lines (quadratic in its length);
    # now a fraction of a second. A comment: the map is the one the other lines give.
    (tmp_path / "m.pgm").write_bytes(b"P5 2 1 255 \x00\xff")
    head = (
        "image: m.pgm\nresolution:\t0.05\norigin: [1.5, -2.0, 0.0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    tail = '# "' + unit * (((1 << 20) - len(head) - 8) // len(unit)) + "\n"
    path = tmp_path / "m.yaml"
    path.write_text(head + tail, encoding="utf-8")
    assert path.stat().st_size <= 1 << 20
    grid = read_map(path)
    assert grid.resolution == 0.05
    assert grid.shape == (1, 2)
