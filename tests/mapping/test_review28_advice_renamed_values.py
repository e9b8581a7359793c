"""Following a renamed keyword's warning literally gives the old keyword's result.

``grid_to_msg_fields(trinary=True)`` said "use mode" (``mode=True`` is a
TypeError), ``ScanMapper(occupied=0.7)`` "use hit" (``hit=0.7`` is silently
another sensor model: 0.7 log-odds is probability 0.67) and
``ScanMapper(free=0.4)`` "use miss" (``miss=0.4`` a ValueError). The warning
now writes the keyword with the value it takes, which these tests read back
from the message and pass.
"""

from __future__ import annotations

import ast
import math
import re
import warnings
from typing import Any

import numpy as np
import pytest
from test_review11_mapping_vocabulary import _room_scan

from navkit.mapping import OccupancyGrid, ScanMapper
from navkit.mapping.io import grid_to_msg_fields


def _advice(call: Any, old: str, new: str) -> tuple[Any, Any]:
    """``call()``'s result (it uses ``old``) and the value its warning says to pass as ``new``."""
    with pytest.warns(DeprecationWarning, match=f"{old} is deprecated") as rec:
        result = call()
    found = re.search(rf": use {new}=([^,\s]+)", str(rec[0].message))
    assert found, f"the warning names no value for {new}=: {rec[0].message}"
    return result, ast.literal_eval(found.group(1))


def _map(mapper: ScanMapper) -> np.ndarray:
    mapper.update(_room_scan())
    return mapper.map.logodds


@pytest.mark.parametrize("trinary", [True, False])
def test_trinary_warning_names_the_mode_to_pass(trinary: bool) -> None:
    grid = OccupancyGrid.from_probabilities(np.array([[0.8, 0.1, 0.5]]), resolution=0.1)
    old, mode = _advice(lambda: grid_to_msg_fields(grid, trinary=trinary), "trinary", "mode")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        new = grid_to_msg_fields(grid, mode=mode)
    np.testing.assert_array_equal(new.data, old.data)


@pytest.mark.parametrize(("old", "new", "p"), [("occupied", "hit", 0.7), ("free", "miss", 0.2)])
def test_probability_warning_names_the_log_odds_to_pass(old: str, new: str, p: float) -> None:
    given: dict[str, Any] = {old: p}
    mapper, value = _advice(lambda: ScanMapper(resolution=0.1, **given), old, new)
    assert value == pytest.approx(math.log(p / (1.0 - p)), rel=1e-15)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        following = ScanMapper(resolution=0.1, **{new: value})
    np.testing.assert_array_equal(_map(following), _map(mapper))
