"""Code health of the simulator's modules (review 33).

* The segment-distance loop of the cross-track kernels was written twice, once in
  each kernel (plain and chunked), which must give the same floats: one helper,
  ``_nearer``, now holds it, inlined into both.
* ``sim/_world.py`` kept ``_EMPTY2`` and ``_EMPTY3`` (used nowhere), its
  ``_point_in_solid`` a ``radius`` it never read, and ``sim/_scenario.py``'s
  ``_json_figures`` a ``name`` it never read.

Checked: against HEAD's ``src`` both tests fail (two loops; five unused names).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import numpy as np
import pytest

import navkit.sim
from navkit.sim import _polyline_distance_kernels as kernels

SIM = Path(navkit.sim.__file__).parent


def _segment_loops(tree: ast.AST) -> list[str]:
    """The functions holding a loop that computes a point-to-segment distance."""
    holders = []
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef):
            for inner in ast.walk(node):
                if isinstance(inner, ast.For) and "math.hypot(wx - t * ex" in ast.unparse(inner):
                    holders.append(node.name)
                    break
    return holders


def test_the_segment_loop_is_written_once_and_both_kernels_agree() -> None:
    tree = ast.parse(Path(kernels.__file__).read_text(encoding="utf-8"))
    assert _segment_loops(tree) == ["_nearer"]
    # Degenerate and long paths: zero-length segments, a repeated start, a spike.
    s = np.linspace(0.0, 300.0, 3001)
    path = np.column_stack([s, np.sin(s)])
    path[100:110] = path[100]
    path[2000] = (150.0, 40.0)
    rng = np.random.default_rng(7)
    points = np.concatenate([path[::7] + rng.normal(0.0, 0.5, (429, 2)), [[1e6, -1e6]]])
    plain = np.empty(points.shape[0])
    chunked = np.empty(points.shape[0])
    kernels.point_polyline_distances(points, path, plain)
    kernels.point_polyline_distances_chunked(points, path, kernels.chunk_boxes(path), chunked)
    assert np.array_equal(plain, chunked)


def _unused(path: Path) -> list[str]:
    """Private module-level names used nowhere in src nor tests, and unread parameters."""
    text = path.read_text(encoding="utf-8")
    tree = ast.parse(text)
    found = []
    everywhere = "\n".join(
        p.read_text(encoding="utf-8")
        for root in (SIM.parent, SIM.parents[2] / "tests")
        if root.is_dir()
        for p in root.rglob("*.py")
    )
    for node in tree.body:
        targets = node.targets if isinstance(node, ast.Assign) else []
        for target in targets:
            name = getattr(target, "id", "")
            private = name.startswith("_") and not name.startswith("__")
            if private and len(re.findall(rf"\b{re.escape(name)}\b", everywhere)) <= 1:
                found.append(name)
    for node in ast.walk(tree):
        # Private functions and methods; not dunders (their signatures are Python's).
        if isinstance(node, ast.FunctionDef) and re.fullmatch(r"_[^_].*", node.name):
            read = {n.id for n in ast.walk(node) if isinstance(n, ast.Name)}
            for arg in node.args.args + node.args.kwonlyargs:
                if arg.arg not in {"self", "cls"} and arg.arg not in read:
                    found.append(f"{node.name}({arg.arg})")
    return found


@pytest.mark.parametrize("module", ["_world.py", "_scenario.py", "_polyline_distance_kernels.py"])
def test_no_unused_private_names_or_parameters(module: str) -> None:
    assert _unused(SIM / module) == []
