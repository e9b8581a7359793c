"""Copies and pickles of subclassed filters keep their class and what the subclass adds."""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter, PlanarFusion


class TaggedEKF(ExtendedKalmanFilter):
    """A subclass with an instance ``__dict__`` (it declares no slots)."""

    def __init__(self, x0: Any, P0: Any) -> None:
        super().__init__(x0, P0, angle_states=(0,))
        self.history: list[float] = [1.0]


class SlottedFusion(PlanarFusion):
    """A subclass with slots of its own, one of them private (name-mangled)."""

    __slots__ = ("__secret", "tag")

    def __init__(self) -> None:
        super().__init__(t0=0.0)
        self.tag = [7]
        self.__secret = "s"

    @property
    def secret(self) -> str:
        return self.__secret


COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    lambda obj: pickle.loads(pickle.dumps(obj)),
]


@pytest.mark.parametrize("make_copy", COPIES)
def test_ekf_subclass_copies_whole(make_copy: Callable[[Any], Any]) -> None:
    ekf = TaggedEKF([3.0, 1.0], np.eye(2))
    ekf.update([0.5], lambda x: x[:1], [[1.0, 0.0]], [[1.0]])
    dup = make_copy(ekf)
    assert type(dup) is TaggedEKF
    assert dup.history == [1.0]
    assert dup.angle_states == (0,)
    np.testing.assert_array_equal(dup.x, ekf.x)
    np.testing.assert_array_equal(dup.P, ekf.P)
    # The estimate stays independent of the original's.
    dup.update([0.5], lambda x: x[:1], [[1.0, 0.0]], [[1.0]])
    assert not np.array_equal(dup.x, ekf.x)
    if make_copy is not copy.copy:  # a deep copy or pickle owns its attributes too
        dup.history.append(2.0)
        assert ekf.history == [1.0]


@pytest.mark.parametrize("make_copy", COPIES)
def test_fusion_subclass_copies_whole(make_copy: Callable[[Any], Any]) -> None:
    fusion = SlottedFusion()
    fusion.update_odometry(0.1, 1.0, 0.0, v_variance=1e-3, omega_variance=1e-3)
    dup = make_copy(fusion)
    assert type(dup) is SlottedFusion
    assert dup.tag == [7]
    assert dup.secret == "s"
    assert dup.t == fusion.t
    np.testing.assert_array_equal(dup.x, fusion.x)
    dup.update_odometry(0.2, 1.0, 0.0, v_variance=1e-3, omega_variance=1e-3)
    assert fusion.t == pytest.approx(0.1)
    assert not np.array_equal(dup.x, fusion.x)


def test_base_classes_still_copy_as_before() -> None:
    """The base classes pickle without extra state (and their pickles stay small)."""
    ekf = ExtendedKalmanFilter([1.0], [[2.0]])
    reduced = ekf.__reduce__()
    assert len(reduced) == 2
    dup = pickle.loads(pickle.dumps(ekf))
    assert type(dup) is ExtendedKalmanFilter
    fusion = PlanarFusion(t0=1.0)
    assert len(fusion.__reduce__()) == 2
    assert type(copy.deepcopy(fusion)) is PlanarFusion
