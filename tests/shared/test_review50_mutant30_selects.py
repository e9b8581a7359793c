"""Review 50 (MUTANT30): ``min2`` and ``max2`` refuse two non-numbers of one type.

``navkit._shared.selects`` types ``min2(a, b)`` and ``max2(a, b)`` for numbers
(and booleans) only, as numba's builtins for two arguments. The suite tried
a number and a tuple, which do not unify whatever the check: a mutant
without the check survived, and then typed two tuples of one type (or two
arrays), which unify, and compiled a lexicographic max of tuples (or failed
in lowering, not typing). Both are refused when typed.
"""

from __future__ import annotations

import numba
import numpy as np
import pytest

from navkit._shared.selects import max2, min2


@pytest.mark.parametrize("select", [min2, max2], ids=["min2", "max2"])
def test_two_tuples_or_arrays_of_one_type_are_refused_when_typed(select: object) -> None:
    pairs = numba.njit(lambda: select((1, 2), (3, 4)))
    with pytest.raises(numba.core.errors.TypingError):
        pairs()
    arrays = numba.njit(lambda a: select(a, a))
    with pytest.raises(numba.core.errors.TypingError):
        arrays(np.zeros(2))
    # Numbers of two types still unify, as the builtins' do.
    mixed = numba.njit(lambda: select(2, 1.5))
    assert mixed() == (1.5 if select is min2 else 2.0)
