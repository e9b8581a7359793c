"""The public annotations as a user's type checker sees them (review 10).

``tests/typing_user/user_api.py`` calls the API the way the docstrings and docs/
do (lists and tuples where array_like is documented, star imports); mypy
``--strict`` must accept it. The records whose dataclass fields are arrays declare
their array_like ``__init__`` for type checkers only, so a test also keeps those
declarations in step with the ``__init__`` the dataclass generates at run time.
"""

from __future__ import annotations

import ast
import importlib.util
import inspect
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import navkit.planning
import navkit.planning.grid
import navkit.planning.reactive
from navkit.behaviours import BehaviourTarget, GameState
from navkit.geometry import ImuInBase
from navkit.mapping import LaserScan
from navkit.mapping.io import BagImu, BagOdometry, BagScans, OccupancyGridMsgFields
from navkit.planning import (
    BlendedAttraction,
    CompositeField,
    ConicAttraction,
    GreedyStep,
    KhatibRepulsion,
    ParaboloidAttraction,
    PiecewiseAttraction,
    PiecewiseRepulsion,
    SampledField,
)
from navkit.planning.grid import Path2D
from navkit.sim import Circle, MovingObstacle

ROOT = Path(__file__).resolve().parents[1]
USER_SCRIPT = ROOT / "tests" / "typing_user" / "user_api.py"

ARRAY_RECORDS = [
    LaserScan,
    Circle,
    BehaviourTarget,
    GameState,
    ImuInBase,
    ParaboloidAttraction,
    ConicAttraction,
    BlendedAttraction,
    PiecewiseAttraction,
    KhatibRepulsion,
    PiecewiseRepulsion,
    GreedyStep,
    Path2D,
    SampledField,
    CompositeField,
    BagScans,
    BagOdometry,
    BagImu,
    OccupancyGridMsgFields,
    MovingObstacle,
]
# Declared parameters that are not arrays but still wider than their field.
WIDER = {
    (CompositeField, "fields"): "Iterable[PotentialField]",
    (OccupancyGridMsgFields, "data"): "ArrayLike",
    (MovingObstacle, "shape"): "float | Polygon | ArrayLike",
    # None asks for it to be inferred; the field is always a bool after (review 49).
    (GameState, "has_ball"): "bool | None",
}


@pytest.mark.slow
@pytest.mark.skipif(importlib.util.find_spec("mypy") is None, reason="mypy is not installed")
def test_user_script_type_checks_under_mypy_strict(tmp_path: Path) -> None:
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "mypy",
            "--strict",
            "--cache-dir",
            str(tmp_path / "mypy_cache"),
            str(USER_SCRIPT),
        ],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_planning_all_is_a_literal_union_of_its_halves() -> None:
    # mypy honours only a literal __all__; it must still list exactly both halves.
    assert navkit.planning.__all__ == sorted(
        [*navkit.planning.grid.__all__, *navkit.planning.reactive.__all__]
    )
    tree = ast.parse(Path(navkit.planning.__file__).read_text())
    assigned = [
        node.value
        for node in tree.body
        if isinstance(node, ast.Assign)
        and any(isinstance(t, ast.Name) and t.id == "__all__" for t in node.targets)
    ]
    assert len(assigned) == 1
    assert isinstance(assigned[0], ast.List)
    assert all(isinstance(e, ast.Constant) for e in assigned[0].elts)


def _declared_init(cls: type) -> ast.FunctionDef:
    tree = ast.parse(textwrap.dedent(inspect.getsource(cls)))
    body = tree.body[0]
    assert isinstance(body, ast.ClassDef)
    for node in body.body:
        # A record whose __init__ is its own (BehaviourTarget since review 54, which
        # builds in __new__ too): the one type checkers and users see.
        if isinstance(node, ast.FunctionDef) and node.name == "__init__":
            return node
        if (
            isinstance(node, ast.If)
            and isinstance(node.test, ast.Name)
            and node.test.id == "TYPE_CHECKING"
        ):
            for inner in node.body:
                if isinstance(inner, ast.FunctionDef) and inner.name == "__init__":
                    return inner
    raise AssertionError(f"{cls.__name__} declares no __init__ for type checkers")


@pytest.mark.parametrize("cls", ARRAY_RECORDS, ids=lambda c: c.__name__)
def test_declared_init_matches_the_generated_one(cls: type) -> None:
    declared = _declared_init(cls)
    args = declared.args
    positional = [a.arg for a in args.args][1:]  # drop self
    keyword = [a.arg for a in args.kwonlyargs]
    n_pos_defaults = len(args.defaults)
    pos_defaults = [False] * (len(positional) - n_pos_defaults) + [True] * n_pos_defaults
    kw_defaults = [d is not None for d in args.kw_defaults]
    annotations = {
        a.arg: ast.unparse(a.annotation) for a in [*args.args[1:], *args.kwonlyargs] if a.annotation
    }

    runtime = inspect.signature(cls)
    rt_positional = [
        p.name for p in runtime.parameters.values() if p.kind is p.POSITIONAL_OR_KEYWORD
    ]
    rt_keyword = [p.name for p in runtime.parameters.values() if p.kind is p.KEYWORD_ONLY]
    assert positional == rt_positional
    assert keyword == rt_keyword
    has_default = dict(zip(positional + keyword, pos_defaults + kw_defaults, strict=True))
    for p in runtime.parameters.values():
        assert has_default[p.name] == (p.default is not p.empty), p.name
        # Array fields become ArrayLike; every other annotation is the field's own.
        field_ann = str(p.annotation)
        expected = WIDER.get((cls, p.name), field_ann.replace("FloatArray", "ArrayLike"))
        assert annotations[p.name] == ast.unparse(ast.parse(expected, mode="eval")), p.name
