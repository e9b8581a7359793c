"""A negate spelt as the longest octal int yaml-cpp reads gets its hint (review 53, MUTANT33).

5284292 says what map_server (yaml-cpp, a C stream with the base left to the
text) reads for an integer spelling of ``negate``. A leading 0 and up to 11
octal digits fit a C ``int`` (``017777777777`` is 2**31 - 1); review 52's tests
stopped short of 11 digits, and a mutant matching 10 passed them, giving the
longest spelling no hint. One more (``020000000000``, 2**31) is no int: no hint.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

from navkit.mapping.io import read_map

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_review52_mutant32_map_yaml import _map


@pytest.mark.parametrize(
    ("negate", "hint"),
    [
        ("017777777777", " (map_server reads it as the integer 2147483647: negated; write 1)"),
        ("-017777777777", " (map_server reads it as the integer -2147483647: negated; write 1)"),
        ("000000000000", " (map_server reads it as the integer 0: not negated; write 0)"),
        ("020000000000", ""),
    ],
)
def test_an_octal_negate_of_eleven_digits_is_read_as_map_server_reads_it(
    tmp_path: Path, negate: str, hint: str
) -> None:
    yaml_path = _map(tmp_path, "image: map.pgm", "map.pgm")
    text = yaml_path.read_text(encoding="utf-8")
    yaml_path.write_text(re.sub(r"negate: \S+", f"negate: {negate}", text), encoding="utf-8")
    with pytest.raises(ValueError, match="negate must be 0 or 1") as caught:
        read_map(yaml_path)
    assert str(caught.value).endswith(f"got {negate!r}{hint}")
