"""``NAVKIT_FUZZ_SEED`` varies the public-API fuzz's generated values (review 44, FUZZDRAW).

Unset, the fixed derandomized profile draws the same values every run (CI's); set to
an integer, hypothesis draws others, the same ones again for the same seed.
"""

from __future__ import annotations

import re

import pytest
from hypothesis import given
from hypothesis import strategies as st
from test_public_api_fuzz import fuzz_seed, profile


def _draws(draw_seed: int | None) -> list[bytes]:
    seen: list[bytes] = []

    @profile(draw_seed, 30)
    @given(st.binary(min_size=8, max_size=8))
    def record(value: bytes) -> None:
        seen.append(value)

    record()
    return seen


def test_the_fixed_profile_repeats_its_draws() -> None:
    assert _draws(None) == _draws(None)


def test_a_seed_repeats_its_draws_and_others_differ() -> None:
    first = _draws(44)
    assert len(first) == 30
    assert first == _draws(44)
    assert first != _draws(45)
    assert first != _draws(None)


@pytest.mark.parametrize(("text", "expected"), [(None, None), ("", None), (" 7 ", 7), ("-3", -3)])
def test_the_variable_is_read_as_an_int(
    text: str | None, expected: int | None, monkeypatch: pytest.MonkeyPatch
) -> None:
    if text is None:
        monkeypatch.delenv("NAVKIT_FUZZ_SEED", raising=False)
    else:
        monkeypatch.setenv("NAVKIT_FUZZ_SEED", text)
    assert fuzz_seed() == expected


def test_a_seed_that_is_not_an_int_is_refused_by_name(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("NAVKIT_FUZZ_SEED", "1.5")
    message = "NAVKIT_FUZZ_SEED must be an integer, got '1.5'"
    with pytest.raises(ValueError, match=re.escape(message)):
        fuzz_seed()
