"""Imports only go down the layers; kernels stay private."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "navkit"
BASE = {"errors", "_validation"}
ALLOWED: dict[str, set[str]] = {
    "geometry": {"geometry"},
    "kinematics": {"geometry", "kinematics"},
    "estimation": {"geometry", "kinematics", "estimation"},
    "mapping": {"geometry", "mapping"},
    "planning": {"geometry", "mapping", "planning"},
    "control": {"geometry", "kinematics", "mapping", "planning", "control"},
    "sim": {"geometry", "kinematics", "estimation", "mapping", "planning", "control", "sim"},
}


def navkit_imports(path: Path) -> set[str]:
    """First component after ``navkit.`` of every navkit import in a module."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found: set[str] = set()
    for node in ast.walk(tree):
        names: list[str] = []
        if isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names = [node.module]
        for name in names:
            parts = name.split(".")
            if parts[0] == "navkit" and len(parts) > 1:
                found.add(parts[1])
    return found


@pytest.mark.parametrize("layer", sorted(ALLOWED))
def test_layer_imports_only_downward(layer: str) -> None:
    folder = SRC / layer
    if not folder.is_dir():
        pytest.skip(f"navkit.{layer} does not exist yet")
    for module in folder.rglob("*.py"):
        bad = navkit_imports(module) - ALLOWED[layer] - BASE
        assert not bad, f"{module.relative_to(SRC)} imports navkit.{sorted(bad)} (upward)"


def test_base_modules_import_nothing_above() -> None:
    for name in ("errors.py", "_validation.py", "__init__.py"):
        assert navkit_imports(SRC / name) <= BASE


@pytest.mark.parametrize("layer", sorted(ALLOWED))
def test_public_api_is_declared(layer: str) -> None:
    init = SRC / layer / "__init__.py"
    if not init.is_file():
        pytest.skip(f"navkit.{layer} does not exist yet")
    module = __import__(f"navkit.{layer}", fromlist=["__all__"])
    exported = getattr(module, "__all__", None)
    assert exported, f"navkit.{layer} has no __all__"
    for name in exported:
        assert not name.startswith("_"), f"navkit.{layer} exports private {name}"
        assert hasattr(module, name), f"navkit.{layer}.__all__ names missing {name}"
