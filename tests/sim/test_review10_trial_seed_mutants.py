"""trial_seed keeps the seeds of earlier runs for values below 2**32 (mutation testing).

The CHANGELOG's fix of trial_seed for large values promises that "seeds whose
values are all below 2**32 (those of every run so far) are unchanged": the first
released formula, the first of two 64-bit words NumPy's SeedSequence generates
from the three values, shifted right by one bit.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.sim import trial_seed


def first_release_seed(base: int, case_index: int, trial_index: int) -> int:
    state = np.random.SeedSequence([base, case_index, trial_index])
    return int(state.generate_state(2, dtype=np.uint64)[0] >> np.uint64(1))


@pytest.mark.parametrize(
    "triple",
    [(0, 0, 0), (0, 0, 1), (7, 3, 11), (2**32 - 1, 5, 2**32 - 1), (12345, 2**31, 0)],
)
def test_small_values_give_the_seeds_of_earlier_runs(triple: tuple[int, int, int]) -> None:
    assert trial_seed(*triple) == first_release_seed(*triple)
