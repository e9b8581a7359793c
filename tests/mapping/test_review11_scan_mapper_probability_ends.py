"""ScanMapper's deprecated probabilities: an error names the open range they must lie in.

Both ends of ``occupied`` in (0.5, 1) and ``free`` in (0, 0.5) are refused, so
a message allowing one of them ("<= 1") told the caller something false.
"""

from __future__ import annotations

import re
import warnings
from typing import Any

import pytest

from navkit.mapping import ScanMapper


@pytest.mark.parametrize(
    ("name", "value", "low", "high"),
    [
        ("occupied", 2.0, "0.5", "1"),
        ("occupied", 1.0, "0.5", "1"),
        ("occupied", 0.5, "0.5", "1"),
        ("occupied", -3.0, "0.5", "1"),
        ("free", 0.7, "0", "0.5"),
        ("free", 0.5, "0", "0.5"),
        ("free", 0.0, "0", "0.5"),
        ("free", -1.0, "0", "0.5"),
    ],
)
def test_message_states_both_ends_open(name: str, value: float, low: str, high: str) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        with pytest.raises(ValueError, match=rf"^{name} must be ") as info:
            kwargs: dict[str, Any] = {name: value}
            ScanMapper(**kwargs)
    text = str(info.value)
    assert "<=" not in text and ">=" not in text
    assert f"< {high}" in text and f"> {low}" in text
    assert re.search(rf"got {re.escape(repr(value))}$", text)


@pytest.mark.parametrize(("name", "value"), [("occupied", 0.9999), ("free", 1e-300)])
def test_values_just_inside_are_taken(name: str, value: float) -> None:
    kwargs: dict[str, Any] = {name: value}
    with pytest.warns(DeprecationWarning, match=name):
        ScanMapper(**kwargs)
