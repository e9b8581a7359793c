"""Review 43: ``__array__`` set on an instance, not its class, is read as NumPy reads it.

MUTANT15 found ``has_array_protocol`` looking ``__array__`` up on the type while
NumPy (2.3, 2.4) and the other two protocols' checks look on the instance: such
an object was refused by ``as_pose`` ("got Box") though ``np.asarray`` reads it.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit._shared.validation import has_array_protocol
from navkit.geometry import Pose2D, as_pose


class _Box:
    pass


def _boxed(values: list[float]) -> Any:
    box = _Box()
    box.__array__ = lambda *args, **kwargs: np.array(values)  # type: ignore[attr-defined]
    return box


def test_numpy_reads_an_instances_own_array_method() -> None:
    # The premise: were NumPy to stop reading it, the check should follow.
    assert np.asarray(_boxed([1.0, 2.0, 0.5])).tolist() == [1.0, 2.0, 0.5]


def test_an_instances_own_array_method_is_an_array_protocol() -> None:
    assert has_array_protocol(_boxed([1.0]))
    assert not has_array_protocol(_Box())


def test_as_pose_reads_an_instances_own_array_method() -> None:
    assert as_pose(_boxed([1.0, 2.0, 0.5])) == Pose2D(1.0, 2.0, 0.5)


def test_an_instances_array_of_the_wrong_size_is_refused_as_a_pose() -> None:
    with pytest.raises(ValueError, match="pose"):
        as_pose(_boxed([1.0, 2.0]))
