"""Sums of potential fields: ``sum`` starts from 0, any other number is refused (review 32)."""

from __future__ import annotations

import numpy as np
import pytest

from navkit.planning import ConicAttraction, KhatibRepulsion


def test_sum_of_fields_equals_their_chained_addition() -> None:
    attraction = ConicAttraction((1.0, 0.0))
    repulsion = KhatibRepulsion([[0.5, 0.5]])
    points = [[0.0, 0.0], [0.25, 0.75]]
    np.testing.assert_array_equal(
        sum([attraction, repulsion]).force(points), (attraction + repulsion).force(points)
    )
    assert sum([attraction]) is attraction


@pytest.mark.parametrize("number", [1, -1, 0.0, True])
def test_a_number_other_than_integer_zero_plus_a_field_is_refused(number: object) -> None:
    with pytest.raises(TypeError, match="unsupported operand"):
        number + ConicAttraction((1.0, 0.0))  # type: ignore[operator]
