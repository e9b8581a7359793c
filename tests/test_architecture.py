"""navkit's shape: imports only go down the layers, and only through public faces.

The rule, checked on every module of the package (private ones included):

* layers, bottom to top: ``navkit._shared`` and ``navkit.errors`` ← ``geometry`` ←
  ``kinematics``, ``mapping`` ← ``estimation``, ``planning`` ← ``control`` ←
  ``behaviours`` ← ``sim`` ← ``plot`` ← the command line (``cli``) ← ``__main__``;
* a module may import ``navkit._shared``, ``navkit.errors``, private modules of
  its own subpackage, and the public faces (no ``_``-prefixed part) of
  subpackages in lower layers — nothing else: not a package on its own layer,
  not one above, and not another subpackage's private module;
* the two halves of planning (``navkit.planning.grid``, global planning on cost
  grids, and ``navkit.planning.reactive``) never import each other;
* no relative imports.
"""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "navkit"

BASE = ("_shared", "errors")
RANK: dict[str, int] = {
    "_shared": 0,
    "errors": 0,
    "geometry": 1,
    "kinematics": 2,
    "mapping": 2,
    "estimation": 3,
    "planning": 3,
    "control": 4,
    "behaviours": 5,
    "sim": 6,
    "plot": 7,
    "cli": 8,
    "__main__": 9,
}


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(["navkit", *parts])


def _package_of(path: Path) -> str:
    """The (sub)package a module belongs to, e.g. ``navkit.planning.grid``."""
    parts = list(path.relative_to(SRC).parent.parts)
    if not parts and path.stem not in ("__init__",):
        return f"navkit.{path.stem}"
    return ".".join(["navkit", *parts])


def _imports(path: Path) -> list[tuple[int, str]]:
    """``(line, dotted target)`` of every navkit import in a module.

    ``from navkit.a import _b`` counts as importing ``navkit.a._b``, so a private
    module reached through its package is seen too.
    """
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found: list[tuple[int, str]] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found.extend((node.lineno, alias.name) for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                found.append((node.lineno, "." * node.level + (node.module or "")))
                continue
            module = node.module or ""
            found.append((node.lineno, module))
            found.extend(
                (node.lineno, f"{module}.{alias.name}")
                for alias in node.names
                if alias.name.startswith("_") and not alias.name.startswith("__")
            )
    return [(line, name) for line, name in found if name.split(".")[0] in ("navkit", "")]


def _owner(target: str) -> str:
    """The part of ``target`` before its first private component (its public owner)."""
    parts = target.split(".")
    for i, part in enumerate(parts[1:], start=1):
        if part.startswith("_") and part != "__main__":
            return ".".join(parts[:i])
    return target


def _violation(path: Path, target: str) -> str | None:
    if target.startswith("."):
        return "relative import"
    parts = target.split(".")
    if len(parts) == 1:
        return "imports the navkit package itself"
    top = parts[1]
    if top in BASE:
        return None
    own_package = _package_of(path)
    own_top = own_package.split(".")[1] if "." in own_package else ""
    if top not in RANK:
        return f"imports unknown layer navkit.{top}"
    if own_top in BASE or own_top not in RANK:
        return "the base layer imports nothing above it"
    is_private = _owner(target) != target
    if top == own_top:
        if own_top == "planning":
            halves = {"grid", "reactive"}
            own_half = own_package.split(".")[2] if own_package.count(".") >= 2 else None
            target_half = parts[2] if len(parts) > 2 and parts[2] in halves else None
            if own_half and target_half and own_half != target_half:
                return "the two halves of planning never import each other"
        if is_private and _owner(target) != own_package:
            return "imports another subpackage's private module"
        return None
    if RANK[top] >= RANK[own_top]:
        return f"imports navkit.{top}, which is not below {own_top}"
    if is_private:
        return "imports a private module of another subpackage"
    return None


MODULES = sorted(SRC.rglob("*.py"))


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(SRC)))
def test_imports_follow_the_layers(path: Path) -> None:
    problems = [
        f"line {line}: {target}: {why}"
        for line, target in _imports(path)
        if (why := _violation(path, target)) is not None
    ]
    assert not problems, f"{path.relative_to(SRC)}:\n" + "\n".join(problems)


def test_every_module_belongs_to_a_layer() -> None:
    for path in MODULES:
        rel = path.relative_to(SRC)
        top = rel.parts[0] if len(rel.parts) > 1 else rel.stem
        assert top in RANK or top == "__init__", f"{rel} is in no layer of {sorted(RANK)}"


def test_the_checker_sees_violations() -> None:
    """The rule itself: private, upward and sibling imports are caught."""
    planning = SRC / "planning" / "grid" / "_x.py"
    mapping = SRC / "mapping" / "_x.py"
    assert _violation(planning, "navkit.mapping") is None
    assert _violation(planning, "navkit._shared.lines") is None
    assert _violation(planning, "navkit.planning.grid._astar") is None
    assert _violation(planning, "navkit.mapping._grid") is not None
    assert _violation(planning, "navkit.planning.reactive") is not None
    assert _violation(planning, "navkit.control") is not None
    assert _violation(planning, "navkit.estimation") is not None
    assert _violation(mapping, "navkit.kinematics") is not None
    assert _violation(mapping, ".x") is not None
    assert _violation(SRC / "_shared" / "x.py", "navkit.geometry") is not None


PACKAGES = sorted(
    _module_name(init)
    for init in SRC.rglob("__init__.py")
    if not any(part.startswith("_") for part in init.relative_to(SRC).parent.parts)
    and init.parent != SRC
)


@pytest.mark.parametrize("package", PACKAGES)
def test_public_api_is_declared(package: str) -> None:
    module = importlib.import_module(package)
    exported = getattr(module, "__all__", None)
    assert exported, f"{package} has no __all__"
    assert len(set(exported)) == len(exported), f"{package}.__all__ repeats a name"
    for name in exported:
        assert not name.startswith("_"), f"{package} exports private {name}"
        assert hasattr(module, name), f"{package}.__all__ names missing {name}"
