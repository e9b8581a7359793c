"""The Field D* heap's descent compares first key components as integers.

Review 48 (issue 17): the tournament of a dequeue's descent reads the four
children's first components as their int64 bit patterns, which order as the
float64 values do for non-negative keys (+0.0 up to +inf; D* Lite's keys are
sums of non-negative terms), and falls back to the float comparison of whole
keys when any of the four has its sign bit set (a negative key, or -0.0, equal
to +0.0 as a float but not as bits). The heap must stay the same heap, slot for
slot, as the model of whole float keys compared at every level (review 23's),
on keys where the bit patterns and the floats disagree: negative values,
-0.0 next to +0.0, subnormals, inf.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from test_review23_fd_heap_tournament import NODES, _check

from hypothesis_twins import slow_twin

# Values whose int64 bit patterns misorder or mistie them as floats: negatives
# (their patterns order backwards), -0.0 (== +0.0, but not as bits), and the
# non-negative ones the searches use, where bits and floats agree.
SIGNED = [-3.0, -1.0, -5e-324, -0.0, 0.0, 5e-324, 1.0, 1.5, 2.0, 1e300, np.inf]
values = st.sampled_from(SIGNED)
ops = st.lists(
    st.tuples(
        st.sampled_from(["push", "push", "push", "pop", "remove"]),
        st.integers(0, NODES - 1),
        values,
        values,
    ),
    min_size=50,
    max_size=600,
)


@settings(max_examples=60, deadline=None)
@given(ops)
def test_signed_keys_leave_the_heap_of_float_comparisons(
    sequence: list[tuple[str, int, float, float]],
) -> None:
    _check(sequence)


test_signed_keys_leave_the_heap_of_float_comparisons_thoroughly = slow_twin(
    test_signed_keys_leave_the_heap_of_float_comparisons, max_examples=400
)


def test_negative_first_components_drain_in_float_order() -> None:
    # Full families of negative first components at every level: as bits their
    # order is reversed, so a descent on bits alone would follow the largest child.
    rng = np.random.default_rng(48)
    sequence = [("push", node, -float(rng.integers(1, 40)), float(rng.integers(0, 3)))
                for node in rng.permutation(NODES)]  # fmt: skip
    sequence += [("pop", 0, 0.0, 0.0)] * NODES
    assert _check(sequence) == NODES


def test_minus_zero_ties_plus_zero_and_the_second_components_decide() -> None:
    # -0.0 and +0.0 are one first component: the pops follow the second ones.
    sequence = [("push", node, -0.0 if node % 2 else 0.0, float((7 * node) % 23))
                for node in range(64)]  # fmt: skip
    sequence += [("pop", 0, 0.0, 0.0)] * 64
    assert _check(sequence) == 64
