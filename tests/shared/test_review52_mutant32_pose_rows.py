"""Two poses given for points: both readings named with their shapes (review 52, MUTANT32).

PIPELINE's hint for an ``(N, 3)`` array where points ``(N, 2)`` are wanted
names rows of poses first and, where the array could be transposed points
too (``(2, 3)``), that reading with the transpose's shape. Its tests did not
check that shape: a mutant naming the array's own shape, ``(2, 3)``, passed.
"""

from __future__ import annotations

from navkit._shared.validation import transposed_hint


def test_two_poses_name_both_readings_with_their_shapes() -> None:
    assert transposed_hint((2, 3), (None, 2)) == (
        " (rows of poses [x, y, theta]? pass its [:, :2], shape (2, 2); "
        "or, if it is transposed, one column per item, its .T, shape (3, 2))"
    )


def test_three_poses_are_named_as_rows_of_poses_only() -> None:
    assert transposed_hint((3, 3), (None, 2)) == (
        " (rows of poses [x, y, theta]? pass its [:, :2], shape (3, 2))"
    )
