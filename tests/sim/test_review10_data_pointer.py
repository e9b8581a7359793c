"""A missing data set points to the page that says where to get it.

navkit installed from a wheel has no ``../shared/data``: the experiments that
run on real maps then raise ``DataNotFoundError``. Its message names the
documentation's "Data sets" page (``docs/data.md``), and that page lists every
path navkit's code looks up with ``find_data``, so a user can rebuild the folder.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from navkit.errors import DataNotFoundError
from navkit.sim.scenarios import _data, find_data
from navkit.sim.scenarios._data import ENV_VAR

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "src"
PAGE = ROOT / "docs" / "data.md"


def test_page_exists_and_is_in_the_nav() -> None:
    text = PAGE.read_text(encoding="utf-8")
    assert text.startswith("# Data sets\n")
    assert "- Data sets: data.md" in (ROOT / "mkdocs.yml").read_text(encoding="utf-8")


@pytest.mark.parametrize("how", ["data_dir", "installed"])
def test_not_found_message_names_the_data_sets_page(
    how: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    work = tmp_path / "a" / "b" / "c" / "d"  # no shared/data here or up to 3 levels up
    work.mkdir(parents=True)
    monkeypatch.chdir(work)
    monkeypatch.delenv(ENV_VAR, raising=False)
    wanted = "ros-map-server-maps/turtlebot3_world/map.yaml"
    with pytest.raises(DataNotFoundError) as caught:
        if how == "data_dir":
            find_data(wanted, data_dir=work)
        else:
            # As from a wheel: site-packages has no checkout root beside it.
            module = tmp_path / "venv" / "lib" / "python3.11" / "site-packages" / "navkit"
            monkeypatch.setattr(_data, "__file__", str(module / "sim" / "scenarios" / "_data.py"))
            find_data(wanted)
    message = str(caught.value)
    assert "'Data sets' page" in message
    assert "docs/data.md" in message
    # The pointer adds to the existing advice; it does not replace it.
    assert ENV_VAR in message and "--data" in message and "not found in" in message
    assert "\n" not in message  # the command line prints it as one error line


def _module_file(module: str) -> Path:
    base = SRC.joinpath(*module.split("."))
    package = base / "__init__.py"
    return package if package.is_file() else base.with_suffix(".py")


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _string_constant(module: str, name: str, seen: frozenset[str] = frozenset()) -> str:
    """The str a module-level ``name`` holds in ``module`` (following its imports)."""
    key = f"{module}.{name}"
    assert key not in seen, f"import cycle resolving {key}"
    tree = ast.parse(_module_file(module).read_text(encoding="utf-8"))
    for node in tree.body:
        if isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            if any(isinstance(t, ast.Name) and t.id == name for t in targets):
                value = node.value
                assert isinstance(value, ast.Constant) and isinstance(value.value, str), (
                    f"{key} is not a str literal: find_data's argument cannot be checked"
                )
                return value.value
        if isinstance(node, ast.ImportFrom) and node.module is not None:
            for alias in node.names:
                if (alias.asname or alias.name) == name:
                    assert node.level == 0, f"relative import of {name} in {module}"
                    return _string_constant(node.module, alias.name, seen | {key})
    raise AssertionError(f"{name} is not defined at module level in {module}")


def _find_data_paths() -> dict[str, list[str]]:
    """Every path passed to ``find_data`` in src/navkit, with where it is passed."""
    found: dict[str, list[str]] = {}
    for path in sorted((SRC / "navkit").rglob("*.py")):
        module = _module_name(path)
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if not isinstance(node, ast.Call):
                continue
            func = node.func
            called = func.id if isinstance(func, ast.Name) else getattr(func, "attr", None)
            if called != "find_data":
                continue
            where = f"{path.relative_to(ROOT)}:{node.lineno}"
            assert node.args, f"{where}: find_data without a positional path"
            arg = node.args[0]
            if isinstance(arg, ast.Constant) and isinstance(arg.value, str):
                relative = arg.value
            elif isinstance(arg, ast.Name):
                relative = _string_constant(module, arg.id)
            else:
                raise AssertionError(f"{where}: find_data's path is neither a literal nor a name")
            found.setdefault(relative, []).append(where)
    return found


def test_every_path_navkit_looks_up_is_on_the_data_sets_page() -> None:
    paths = _find_data_paths()
    # The greedy experiment's map and the Willow Garage map of demo and diff-astar.
    assert len(paths) >= 2, paths
    text = PAGE.read_text(encoding="utf-8")
    sections = {line[3:].strip() for line in text.splitlines() if line.startswith("## ")}
    for relative, where in paths.items():
        assert f"`{relative}`" in text, f"{relative} (find_data at {where}) is not on docs/data.md"
        folder = relative.split("/", 1)[0]
        assert folder in sections, f"docs/data.md has no section for {folder}"


def test_the_path_finder_resolves_imported_constants() -> None:
    # The scan above must see through `from ... import WILLOW`: demo and
    # diff-astar pass a name defined in another module.
    paths = _find_data_paths()
    assert any(
        where.startswith("src/navkit/sim/scenarios/_demo.py")
        for wheres in paths.values()
        for where in wheres
    ), paths
