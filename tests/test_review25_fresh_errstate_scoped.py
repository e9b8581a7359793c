"""navkit never changes numpy's error state beyond a ``with np.errstate`` block (review 25).

``tests/conftest.py`` gives every test the error state numpy had before it (an
interrupt inside ``np.errstate.__enter__``, Python code, leaked one into later
tests). That also hides a leak of navkit's own: a call returning, or raising,
with numpy's error state changed would pass every test. Scoped blocks cannot
leak on a return or an exception, so the source is checked for anything else
(``np.seterr``, ``np.seterrcall``, an errstate entered by hand or kept), and
the public calls that use such blocks are run, returning and raising, with the
state compared in the test itself.
"""

from __future__ import annotations

import ast
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

import navkit
from navkit.geometry import wrap_angle

_SRC = Path(navkit.__file__).resolve().parent
_SETTERS = {"seterr", "seterrcall", "_seterrobj", "seterrobj"}


def _errstate_uses(tree: ast.AST) -> tuple[list[int], list[int]]:
    """Lines calling numpy's error-state setters, and ``errstate(...)`` outside a ``with``."""
    scoped: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.With | ast.AsyncWith):
            scoped.update(id(item.context_expr) for item in node.items)
        elif isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            scoped.update(id(d) for d in node.decorator_list)  # @np.errstate(...) is scoped
    setters: list[int] = []
    loose: list[int] = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        func = node.func
        name = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")
        if name in _SETTERS:
            setters.append(node.lineno)
        elif name == "errstate" and id(node) not in scoped:
            loose.append(node.lineno)
    return setters, loose


def test_the_checker_finds_what_it_looks_for() -> None:
    source = (
        "import numpy as np\n"
        "np.seterr(all='ignore')\n"
        "state = np.errstate(over='ignore')\n"
        "with np.errstate(over='ignore'):\n"
        "    pass\n"
    )
    assert _errstate_uses(ast.parse(source)) == ([2], [3])


def test_the_source_changes_numpys_error_state_only_in_with_blocks() -> None:
    found = {}
    files = sorted(_SRC.rglob("*.py"))
    assert len(files) > 50
    uses = 0
    for path in files:
        text = path.read_text(encoding="utf-8")
        uses += text.count("errstate(")
        setters, loose = _errstate_uses(ast.parse(text))
        # Docstring examples are not parsed as code here; a setter there would still
        # be found by the docstring tests' own state checks, not this one.
        if setters or loose:
            found[str(path.relative_to(_SRC))] = (setters, loose)
    assert uses > 20  # the check reads the files that scope their error states
    assert found == {}


def _state() -> tuple[dict[str, str], object]:
    return np.geterr(), np.geterrcall()


# Public calls whose implementation enters np.errstate blocks: each with a good input
# and one it refuses.
_CALLS: dict[str, tuple[Callable[[], object], Callable[[], object]]] = {
    "wrap_angle": (lambda: wrap_angle(np.array([1e308, -4.0])), lambda: wrap_angle("x")),
}


def _more_calls() -> None:
    from navkit.kinematics import DiffDrive
    from navkit.mapping import OccupancyGrid

    grid = OccupancyGrid(np.array([[1e6, -1e6], [0.0, 3.0]], np.float32), resolution=0.1)
    _CALLS["OccupancyGrid.probability"] = (
        grid.probability,
        lambda: OccupancyGrid(np.zeros((3, 3)), resolution=-1.0),
    )
    drive = DiffDrive(wheel_radius=1e6, track=1e-6)
    # Refused after their np.errstate blocks: twists that overflow float64.
    _CALLS["DiffDrive.forward_batch"] = (
        lambda: drive.forward_batch(np.array([[1.0, 2.0], [1.0, -1.0]])),
        lambda: drive.forward_batch(np.array([[1e300, 1.0], [1.0, -1.0]])),
    )
    _CALLS["DiffDrive.forward"] = (
        lambda: drive.forward([1.0, 2.0]),
        lambda: drive.forward([1e300, -1e300]),
    )


_more_calls()


@pytest.mark.parametrize("name", sorted(_CALLS))
def test_public_calls_leave_numpys_error_state_as_they_found_it(name: str) -> None:
    good, bad = _CALLS[name]
    with np.errstate(divide="raise", over="warn", under="call", invalid="print"):
        np.seterrcall(print)
        before = _state()
        good()
        assert _state() == before
        with pytest.raises((TypeError, ValueError)):
            bad()
        assert _state() == before
