"""``positional_deprecated``'s refusals, which no test reached (coverage review, session 30).

Too many positional arguments, or a field given both by position and by
keyword, are ``TypeError`` as Python's own call would raise, before any warning
and before the dataclass is built.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import pytest

from navkit._shared.deprecation import positional_deprecated


@positional_deprecated
@dataclass(frozen=True, kw_only=True)
class Band:
    low: float = 0.0
    high: float = 1.0


def test_more_positional_arguments_than_fields_is_a_type_error() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # refused before warning
        with pytest.raises(TypeError) as info:
            Band(0.1, 0.2, 0.3)  # type: ignore[misc]
    assert str(info.value) == (
        "Band takes at most 2 positional arguments (deprecated; pass low=, high=), got 3"
    )


def test_a_field_by_position_and_by_keyword_is_a_type_error() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(TypeError, match=r"^Band got multiple values for argument 'low'$"):
            Band(0.1, low=0.2)  # type: ignore[misc]


def test_positional_fields_still_work_with_a_warning() -> None:
    with pytest.warns(DeprecationWarning, match=r"^Band\(low, high\) by position"):
        assert Band(0.1, 0.2) == Band(low=0.1, high=0.2)  # type: ignore[misc]
