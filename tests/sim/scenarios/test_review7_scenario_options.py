"""Scenario options: an empty list of targets or pairs, a building that is not a str."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.sim.scenarios import DiffAStar, Greedy, OmniApf


@pytest.mark.parametrize("empty", [[], ()])
def test_no_targets_or_pairs_is_reported_as_a_count(empty: Any, tmp_path: Any) -> None:
    # An empty list used to read as shape (0,): "targets must be 2-D, got shape (0,)"
    # rather than the documented count of 1 to 64.
    with pytest.raises(ValueError, match=r"targets must hold 1 to 64 .*got 0$"):
        OmniApf(targets=empty)
    with pytest.raises(ValueError, match=r"pairs must hold 1 to 64 .*got 0$"):
        Greedy(pairs=empty, data_dir=str(tmp_path))


def test_an_empty_array_is_still_reported_as_a_count(tmp_path: Any) -> None:
    with pytest.raises(ValueError, match=r"got 0$"):
        empty_targets: Any = np.empty((0, 2))
        OmniApf(targets=empty_targets)
    with pytest.raises(ValueError, match=r"got 0$"):
        empty_pairs: Any = np.empty((0, 2, 2))
        Greedy(pairs=empty_pairs, data_dir=str(tmp_path))
    # A target without coordinates is one target of the wrong shape, not none.
    with pytest.raises(ValueError, match="shape"):
        OmniApf(targets=[[]])


@pytest.mark.parametrize("building", [None, 3, ["auto"], b"auto"])
def test_a_building_that_is_not_a_str_is_a_type_error(building: Any) -> None:
    with pytest.raises(TypeError, match="building must be a str"):
        DiffAStar(parts=("house",), building=building)
