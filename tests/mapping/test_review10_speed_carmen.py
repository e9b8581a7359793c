"""read_carmen parses ODOM lines with Python floats (for speed): the same values and the
same refusals as the NumPy parse of the other lines."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import read_carmen

_SCAN = "FLASER 3 1.0 2.0 5.0 0 0 0 0 0 0 1.0 host 1.0\n"


def _write(folder: Path, odom: str) -> Path:
    path = folder / "log.txt"
    path.write_text(_SCAN + odom)
    return path


@pytest.mark.parametrize(
    "fields",
    [
        "0.1 -2.5e-3 3.14159 0 0 0 12.5",
        "1. -.5 0001 4.9e-324 1e-400 -0.0 1234567890.123456789",
        "0.30000000000000004 1e308 -3.0 7 8 9 1e9",
    ],
)
def test_odom_values_are_numpy_parses_of_the_tokens(tmp_path: Path, fields: str) -> None:
    log = read_carmen(_write(tmp_path, f"ODOM {fields} host 1.0\n"))
    tokens = fields.split()
    expected = np.array(tokens, dtype=np.float64)[[0, 1, 2, 6]]
    assert np.array_equal(log.odometry, expected.reshape(1, 4))
    # Same bits (-0.0 included).
    assert log.odometry.tobytes() == expected.tobytes()


@pytest.mark.parametrize(
    ("bad", "message"),
    [
        ("1_0", "must be numbers"),
        ("0x10", "must be numbers"),
        ("1e", "must be numbers"),
        ("1,0", "must be numbers"),
        ("nan", "must be finite, got 'nan'"),
        ("-Infinity", "must be finite, got '-Infinity'"),
        ("1e500", "must be finite, got '1e500'"),
    ],
)
def test_odom_refusals_name_the_line_and_token(tmp_path: Path, bad: str, message: str) -> None:
    path = _write(tmp_path, f"ODOM 0 0 0 0 {bad} 0 1.0 host 1.0\n")
    with pytest.raises(ValueError, match=r"log\.txt:2: malformed ODOM line: pose, speeds") as info:
        read_carmen(path)
    assert message in str(info.value)
    # The FLASER parse (NumPy) refuses the same token with the same words.
    flaser = tmp_path / "scan.txt"
    flaser.write_text(f"FLASER 3 1.0 2.0 5.0 0 0 0 0 0 0 {bad} host 1.0\n")
    with pytest.raises(ValueError, match=r"scan\.txt:1: malformed FLASER line") as other:
        read_carmen(flaser)
    assert message in str(other.value)


def test_first_non_finite_token_is_named(tmp_path: Path) -> None:
    path = _write(tmp_path, "ODOM 0 inf 0 0 nan 0 1.0\n")
    with pytest.raises(ValueError, match="must be finite, got 'inf'"):
        read_carmen(path)
