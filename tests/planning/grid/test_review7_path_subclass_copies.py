"""Subclasses of Path2D copy and pickle whole, with read-only points."""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest

from navkit.planning import Path2D

COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    lambda obj: pickle.loads(pickle.dumps(obj)),
]


class TaggedPath(Path2D):
    pass


@dataclass(frozen=True, slots=True)
class NamedPath(Path2D):
    name: str = ""


@pytest.mark.parametrize("make_copy", COPIES)
def test_path_subclasses_copy_whole(make_copy: Callable[[Any], Any]) -> None:
    points = np.array([[0.0, 0.0], [1.0, 1.0]])
    tagged = TaggedPath(points, "grid", 1.5, 1.5, 3)
    object.__setattr__(tagged, "note", [1])
    named = NamedPath(points, "world", 2.0, 1.4, 4, name="n")
    for path, check in ((tagged, lambda p: p.note == [1]), (named, lambda p: p.name == "n")):
        out = make_copy(path)
        assert type(out) is type(path) and check(out)
        np.testing.assert_array_equal(out.points, path.points)
        assert (out.frame, out.cost, out.length, out.expanded) == (
            path.frame, path.cost, path.length, path.expanded
        )
        assert not out.points.flags.writeable
