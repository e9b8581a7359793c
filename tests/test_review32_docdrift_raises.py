"""Bad input raises what the Raises section documents, for the calls a docs review found.

A sweep of the fuzz catalogues (``tests/fuzz``) over every public callable
compared each exception raised on hostile input with the callable's numpydoc
``Raises`` section; these calls raised a type their section did not name (or
had no section). Each case triggers the error and finds its type (or a base
of it) in the section.
"""

from __future__ import annotations

import inspect
import re
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import test_docstrings as docstrings
from navkit.geometry import Pose2D
from navkit.kinematics import OmniDrive
from navkit.mapping import ScanMatcher
from navkit.planning.grid import FieldDStar
from navkit.planning.reactive import BlendedAttraction
from navkit.sim import ScenarioResult, Table


def _planned() -> FieldDStar:
    planner = FieldDStar(np.ones((5, 5)))
    planner.plan((0, 0), (5, 5))
    return planner


def _walled() -> FieldDStar:
    costs = np.ones((5, 5))
    costs[1:3, 1:3] = np.inf
    planner = FieldDStar(costs)
    planner.plan((0, 0), (5, 5))
    return planner


# (documented callable, the bad call, the exception it raises)
CASES: list[tuple[Callable[..., Any], Callable[[], Any], type[Exception]]] = [
    (FieldDStar.replan, lambda: _planned().replan(start_node=(1.5, 0)), TypeError),
    (FieldDStar.replan, lambda: _planned().replan(start_node="ab"), TypeError),
    (FieldDStar.replan, lambda: _planned().replan(start_node=(9, 9)), ValueError),
    (FieldDStar.replan, lambda: _planned().replan(start_node=(1,)), ValueError),
    (FieldDStar.replan, lambda: _walled().replan(start_node=(2, 2)), ValueError),
    (FieldDStar.replan, lambda: FieldDStar(np.ones((3, 3))).replan(), RuntimeError),
    (BlendedAttraction.sigma, lambda: BlendedAttraction((0.0, 0.0)).sigma([1j]), TypeError),
    (BlendedAttraction.sigma, lambda: BlendedAttraction((0.0, 0.0)).sigma(["a"]), TypeError),
    (BlendedAttraction.sigma, lambda: BlendedAttraction((0.0, 0.0)).sigma([np.nan]), ValueError),
    (BlendedAttraction.sigma, lambda: BlendedAttraction((0.0, 0.0)).sigma([np.inf]), ValueError),
    (OmniDrive.three_wheel, lambda: OmniDrive.three_wheel(wheel_radius=np.nan, base_radius=0.2),
     ValueError),
    (OmniDrive.three_wheel, lambda: OmniDrive.three_wheel(wheel_radius="a", base_radius=0.2),
     TypeError),
    (Table.render, lambda: _table().render(digits=1.5), TypeError),
    (Table.render, lambda: _table().render(digits=0), ValueError),
    (ScenarioResult.table, lambda: ScenarioResult("x", 0, (), (_table(),)).table(digits=True),
     TypeError),
    (ScenarioResult.table, lambda: ScenarioResult("x", 0, (), (_table(),)).table(digits=18),
     ValueError),
    (ScanMatcher.pyramid, lambda: ScanMatcher().pyramid(None), TypeError),  # type: ignore[arg-type]
    (Pose2D.__matmul__, lambda: Pose2D(0.0, 0.0, 0.0) @ [1.0, 2.0], ValueError),
    (Pose2D.__matmul__, lambda: Pose2D(0.0, 0.0, 0.0) @ ["a", 0.0, 0.0], TypeError),
]  # fmt: skip


def _table() -> Table:
    return Table("t", ("a",), ((1.0,),))


def _documented(func: Callable[..., Any]) -> set[str]:
    """Exception names on the entry lines of ``func``'s Raises section."""
    section = docstrings._sections(docstrings._own_doc(func)).get("Raises", "")
    names: set[str] = set()
    for line in section.splitlines():
        if line and not line[0].isspace():
            names |= {name.rsplit(".", 1)[-1] for name in re.findall(r"[A-Za-z_][\w.]*", line)}
    return names


@pytest.mark.parametrize(
    ("func", "bad_call", "kind"),
    CASES,
    ids=[f"{f.__qualname__}-{k.__name__}-{i}" for i, (f, _, k) in enumerate(CASES)],
)
def test_the_raised_type_is_documented(
    func: Callable[..., Any], bad_call: Callable[[], Any], kind: type[Exception]
) -> None:
    with pytest.raises(kind) as raised:
        bad_call()
    documented = _documented(func)
    bases = {klass.__name__ for klass in inspect.getmro(type(raised.value))}
    assert documented & bases, (
        f"{func.__qualname__} raised {type(raised.value).__name__} ({raised.value}); its Raises"
        f" section names only {sorted(documented) or 'nothing'}"
    )
