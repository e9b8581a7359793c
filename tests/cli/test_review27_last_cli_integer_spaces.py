"""An integer option reads the text it checked: the stripped one (review 27).

Review 26 checked ``text.strip()`` against the integer pattern and then read
``int(text)``. ``str.strip()`` takes the ASCII separators ``\\x1c``-``\\x1f``
for spaces and ``int()`` does not, so ``--trials $'\\x1c5'`` was refused as
"must be in [1, 100000], got an integer of 1 characters", the message for
integers beyond ``int()``'s digit limit; ``--start $'\\x1c5,0'`` was read as
(5, 0). Both read the stripped number now.
"""

from __future__ import annotations

import argparse

import pytest

from navkit.cli._parser import _count, _point


@pytest.mark.parametrize("space", ["\x1c", "\x1d", "\x1e", "\x1f", " ", "\u3000"])
def test_an_integer_between_characters_strip_removes_is_read_like_a_point(space: str) -> None:
    assert _count(1, 100)(f"{space}5{space}") == 5
    assert _point(f"{space}5{space},0") == (5.0, 0.0)


def test_an_integer_beyond_the_digit_limit_still_says_its_length() -> None:
    with pytest.raises(argparse.ArgumentTypeError, match="got an integer of 5001 characters"):
        _count(0, 100)(" 1" + "0" * 5000 + " ")
