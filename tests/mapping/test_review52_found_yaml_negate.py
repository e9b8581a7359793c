"""``negate`` spelt as map_server's reader takes it, not as its documentation gives it (review 52).

map_server (and Nav2's) read ``negate`` with yaml-cpp's ``as<int>()``, a C
stream with the base left to the text: ``00`` is 0, ``0x1`` is 1, ``010`` is 8,
and any non-zero integer negates. navkit refuses every value but 0, 1, true
and false (review 51 kept the refusal: "010" meaning 8 is no reading to guess);
the refusal now says what map_server made of the value and what to write, for
a map written for it. A spelling yaml-cpp cannot read either gets no hint.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from navkit.mapping.io import read_map

TEXT = "image: m.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: {}\n"
TEXT += "occupied_thresh: 0.65\nfree_thresh: 0.196\n"


def _write(folder: Path, negate: str) -> Path:
    (folder / "m.pgm").write_bytes(b"P5 2 1 255 \x00\xff")
    path = folder / "m.yaml"
    path.write_text(TEXT.format(negate), encoding="utf-8")
    return path


@pytest.mark.parametrize(
    ("negate", "number", "verdict", "write"),
    [
        ("00", 0, "not negated", 0),
        ("0x1", 1, "negated", 1),
        ("0X1F", 31, "negated", 1),
        ("2", 2, "negated", 1),
        ("010", 8, "negated", 1),
        ("-1", -1, "negated", 1),
        ("0x7fffffff", 2**31 - 1, "negated", 1),
    ],
)
def test_an_integer_spelling_is_refused_saying_what_map_server_reads(
    tmp_path: Path, negate: str, number: int, verdict: str, write: int
) -> None:
    with pytest.raises(ValueError) as caught:
        read_map(_write(tmp_path, negate))
    assert str(caught.value).endswith(
        f"negate must be 0 or 1, got {negate if negate in ('2', '-1') else repr(negate)} "
        f"(map_server reads it as the integer {number}: {verdict}; write {write})"
    )


@pytest.mark.parametrize("negate", ["08", "0x", "1.0", "0x80000000", "2147483648", "[1]"])
def test_a_spelling_yaml_cpp_cannot_read_as_an_int_gets_no_hint(
    tmp_path: Path, negate: str
) -> None:
    with pytest.raises(ValueError, match=r"negate must be 0 or 1, got [^(]*$"):
        read_map(_write(tmp_path, negate))


@pytest.mark.parametrize(("negate", "negated"), [("0", False), ("1", True), ("true", True)])
def test_the_documented_values_still_read(tmp_path: Path, negate: str, negated: bool) -> None:
    grid = read_map(_write(tmp_path, negate))
    # The image's black pixel is occupied unless negated (then the white one is).
    assert bool(grid.occupied()[0, 0]) is not negated
