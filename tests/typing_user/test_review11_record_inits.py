"""The array_like ``__init__`` declared for type checkers by the records review 11 widened.

``tests/typing_user/user_api.py`` builds them from lists, as their docstrings do;
here each declaration is kept in step with the ``__init__`` the dataclass
generates at run time, by the check review 10 applies to its records.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path
from types import ModuleType

import pytest

from navkit.mapping.io import BagImu, BagOdometry, BagScans, OccupancyGridMsgFields
from navkit.sim import MovingObstacle

RECORDS = [BagScans, BagOdometry, BagImu, OccupancyGridMsgFields, MovingObstacle]
# Declared parameters wider than their field in more than FloatArray -> ArrayLike.
WIDER = {
    (OccupancyGridMsgFields, "data"): "ArrayLike",
    (MovingObstacle, "shape"): "float | Polygon | ArrayLike",
}


def _review10() -> ModuleType:
    path = Path(__file__).resolve().parents[1] / "test_review10_user_typing.py"
    spec = importlib.util.spec_from_file_location("_review10_user_typing", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


REVIEW10 = _review10()


@pytest.mark.parametrize("cls", RECORDS, ids=lambda c: c.__name__)
def test_declared_init_matches_the_generated_one(
    cls: type, monkeypatch: pytest.MonkeyPatch
) -> None:
    for (owner, name), annotation in WIDER.items():
        if owner is cls:
            monkeypatch.setitem(REVIEW10.WIDER, (owner, name), annotation)
    REVIEW10.test_declared_init_matches_the_generated_one(cls)
