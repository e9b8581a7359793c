"""A negate spelt with many leading zeros gets map_server's reading as a hint (review 54, FOUND8).

5284292 says, for a refused integer spelling of ``negate``, what map_server
(yaml-cpp: a C stream, the base left to the text) reads from it. Its pattern
took at most 11 octal or 8 hexadecimal digits, the most a C ``int`` holds, so
``0000000000001`` or ``0x000000001`` (leading zeros, which C reads past: 1
both) got no hint, though still refused. Leading zeros are now dropped before
the digits are counted; a spelling whose value overflows an ``int`` still gets
none (yaml-cpp cannot read it as an ``int``), and so does one that is no C
integer at all.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from navkit.mapping.io import read_map
from navkit.mapping.io._map_files import _c_int

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_review52_mutant32_map_yaml import _map

INT_MIN, INT_MAX = -(2**31), 2**31 - 1


def _hint(number: int) -> str:
    verdict = "negated" if number else "not negated"
    return f" (map_server reads it as the integer {number}: {verdict}; write {int(number != 0)})"


@pytest.mark.parametrize(
    ("negate", "number"),
    [
        ("0000000000001", 1),
        ("0x000000001", 1),
        ("0x0000000000", 0),
        ("-0x00000000001", -1),
        ("0x0000000007fffffff", INT_MAX),
        ("0000000000000000000000017777777777", INT_MAX),
        ("-0000000000000020000000000", INT_MIN),
        ("+000000000000000000001", 1),
        ("0000000000000", 0),
        ("0x000000000080000000", None),
        ("000000000000000000000020000000000", None),
        ("00000000000008", None),
        ("0x000000000g", None),
    ],
)
def test_leading_zeros_keep_the_hint(tmp_path: Path, negate: str, number: int | None) -> None:
    yaml_path = _map(tmp_path, "image: map.pgm", "map.pgm")
    text = yaml_path.read_text(encoding="utf-8")
    yaml_path.write_text(re.sub(r"negate: \S+", f"negate: {negate}", text), encoding="utf-8")
    with pytest.raises(ValueError, match="negate must be 0 or 1") as caught:
        read_map(yaml_path)
    hint = "" if number is None else _hint(number)
    assert str(caught.value).endswith(f"got {negate!r}{hint}")


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    value=st.one_of(
        st.integers(INT_MIN, INT_MAX),
        st.integers(-(2**40), 2**40),
        st.sampled_from([INT_MIN, INT_MAX, INT_MAX + 1, INT_MIN - 1, 0]),
    ),
    zeros=st.integers(0, 40),
    base=st.sampled_from([8, 16]),
    plus=st.booleans(),
    upper=st.booleans(),
)
def test_a_c_integer_is_read_whatever_its_leading_zeros(
    value: int, zeros: int, base: int, plus: bool, upper: bool
) -> None:
    # The oracle: C's reading of the spelling, by Python's int() of its digits.
    digits = format(abs(value), "o" if base == 8 else "x")
    digits = digits.upper() if upper else digits
    prefix = "0" if base == 8 else ("0X" if upper else "0x")
    sign = "-" if value < 0 else ("+" if plus else "")
    text = f"{sign}{prefix}{'0' * zeros}{digits}"
    expected = value if INT_MIN <= value <= INT_MAX else None
    assert int(text[len(sign) + len(prefix) :], base) == abs(value)
    assert _c_int(text) == expected, text


def test_a_long_run_of_zeros_is_read_as_c_reads_it() -> None:
    # Dropped by hand, not matched by the pattern (which would backtrack over them).
    assert _c_int("0" * 300_000 + "1") == 1
    assert _c_int("-0x" + "0" * 300_000 + "7fffffff") == -INT_MAX
    assert _c_int("0x" + "0" * 300_000 + "g") is None
    assert _c_int("0" * 300_000 + "8") is None
