"""Review 54 (MUTANT34): which float32 resolutions count cells of a decimal, and huge ones.

``navkit._shared.float32.intended_resolution`` takes a float32 resolution for the
shortest decimal float32 rounds to it when that decimal has at most 6
significant digits (C's ``FLT_DIG``: any such decimal survives float32), and
for itself otherwise. The review-53 tests used decimals of at most 3 digits,
so counting a 6-digit decimal as "no decimal" (``> 6`` made ``>= 6``), or a
7-digit one as a decimal (``FLT_DIG`` 7), or dropping the guard that keeps a
resolution beyond float32's range out of the cast, all passed them.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.planning import ConicAttraction, sample_field

#: Decimals of exactly 6 significant digits whose float32 lies below them: at the
#: float32 itself, n of these decimals are a little more than n cells.
SIX_DIGITS = (0.0123457, 0.100001, 0.0543211, 0.0256789)

#: Decimals of 7 significant digits whose float32 lies above them: no decimal a float32
#: keeps stands behind that float32, so n of its own cells are n cells.
SEVEN_DIGITS = (0.1234567, 0.2345671)


def _single(value: float) -> float:
    return float(np.float32(value))


def test_the_premises_hold() -> None:
    for d in SIX_DIGITS:
        assert _single(d) < d
        assert np.format_float_scientific(np.float32(d), unique=True).count("e") == 1
        digits = np.format_float_scientific(np.float32(d), unique=True).split("e")[0]
        assert len(digits.replace(".", "")) == 6
    for d in SEVEN_DIGITS:
        assert _single(d) > d
        digits = np.format_float_scientific(np.float32(d), unique=True).split("e")[0]
        assert len(digits.replace(".", "")) == 7


@pytest.mark.parametrize("decimal", SIX_DIGITS)
@pytest.mark.parametrize("n", [1000, 4096])
def test_a_six_digit_decimal_is_the_cell_of_its_float32(decimal: float, n: int) -> None:
    # As at the decimal itself: n columns, where the float32's own cells are n + 1.
    assert n * decimal / _single(decimal) > n + 1e-6
    want = OccupancyGrid.empty(width=n * decimal, height=decimal, resolution=decimal).shape
    got = OccupancyGrid.empty(width=n * decimal, height=decimal, resolution=_single(decimal))
    assert want == (1, n)
    assert got.shape == want


@pytest.mark.parametrize("decimal", SEVEN_DIGITS)
@pytest.mark.parametrize("n", [1000, 4096])
def test_a_seven_digit_float32_counts_its_own_cells(decimal: float, n: int) -> None:
    res = _single(decimal)
    # n of the float32's cells are more than n cells of the 7-digit decimal.
    assert n * res / decimal > n + 1e-6
    grid = OccupancyGrid.empty(width=n * res, height=res, resolution=res)
    assert grid.shape == (1, n)


def test_a_resolution_beyond_float32_is_refused_without_a_warning() -> None:
    # 1e300 m is no float32 value (its cast would overflow, a RuntimeWarning): the
    # cells are counted in it as given, and then the bound refuses it, naming it.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ValueError, match=r"resolution must lie in .* got 1e\+300"):
            sample_field(
                ConicAttraction((0.0, 0.0)), xlim=(0.0, 1.0), ylim=(-1.0, 0.0), resolution=1e300
            )
