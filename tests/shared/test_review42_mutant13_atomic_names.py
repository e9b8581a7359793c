"""A temporary file's name keeps as much of the target's stem as fits (review 42, MUTANT13).

A mutation review of ``navkit._shared.files`` found two mutants of the name's
shortening passing every test: a name of exactly the file system's limit taken
as too long (``<`` for ``<=``), and the stem shortened two characters at a time.
Both only shortened names that would have fit; the tests checked that names fit,
never that they were as long as allowed. Here the name is checked against the
longest stem prefix whose name fits, found by trying every prefix.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import example, given
from hypothesis import strategies as st

from navkit._shared.files import _temporary_name

TAG = "1f2e3d4c"


def _longest(stem: str, suffix: str, name_max: int) -> str:
    """The name with the longest prefix of ``stem`` that fits ``name_max`` bytes."""
    for k in range(len(stem), -1, -1):
        name = f".{stem[:k]}.{TAG}.tmp{suffix}"
        if k and len(os.fsencode(name)) <= name_max:
            return name
    name = f"..{TAG}.tmp{suffix}"
    return name if len(os.fsencode(name)) <= name_max else f".{TAG}.tmp"


@given(
    stem=st.text(st.sampled_from("aé€𝄞_"), min_size=1, max_size=40),
    suffix=st.sampled_from(["", ".pgm", ".yaml", ".é"]),
    spare=st.integers(-45, 5),
)
@example(stem="a" * 30, suffix=".pgm", spare=0)  # a name of exactly the limit
@example(stem="a" * 30, suffix=".pgm", spare=-1)
@example(stem="a" * 30, suffix=".pgm", spare=-2)
def test_the_temporary_name_keeps_the_longest_stem_that_fits(
    stem: str, suffix: str, spare: int
) -> None:
    full = f".{stem}.{TAG}.tmp{suffix}"
    name_max = len(os.fsencode(full)) + spare
    got = _temporary_name(Path("/folder") / f"{stem}{suffix}", TAG, name_max)
    assert got == _longest(stem, suffix, name_max)
    if spare >= 0:
        assert got == full


@pytest.mark.parametrize("name_max", [255, 64, 40])
def test_a_target_name_at_the_limit_gives_a_temporary_name_at_the_limit(name_max: int) -> None:
    suffix = ".png"
    stem = "m" * (name_max - len(suffix))
    got = _temporary_name(Path(f"{stem}{suffix}"), TAG, name_max)
    assert len(os.fsencode(got)) == name_max
    assert got.endswith(f".{TAG}.tmp{suffix}")
