"""The Python floor: installable with the numpy floor, and what the tools check against.

navkit once claimed Python >= 3.10 while its floor numpy >= 2.3 needs 3.11, and
mypy checked as if on 3.10, where numpy's stubs turn many types into ``Any``
and hide errors.
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

# The oldest Python each numpy minor release installs on (its ``requires-python``).
NUMPY_PYTHON_FLOOR = {
    (2, 0): (3, 9),
    (2, 1): (3, 10),
    (2, 2): (3, 10),
    (2, 3): (3, 11),
    (2, 4): (3, 11),
}


def _pyproject() -> dict[str, object]:
    with (ROOT / "pyproject.toml").open("rb") as file:
        return tomllib.load(file)


def _version(text: str) -> tuple[int, int]:
    parts = re.fullmatch(r"(\d+)\.(\d+)(?:\.\d+)*", text)
    assert parts is not None, text
    return int(parts[1]), int(parts[2])


def _python_floor(data: dict[str, object]) -> tuple[int, int]:
    project = data["project"]
    assert isinstance(project, dict)
    floor = re.fullmatch(r">=\s*([\d.]+)", project["requires-python"])
    assert floor is not None, project["requires-python"]
    return _version(floor[1])


def test_python_floor_installs_the_numpy_floor() -> None:
    data = _pyproject()
    project = data["project"]
    assert isinstance(project, dict)
    # The floor for every Python (not one under a marker, for a newer Python's wheels).
    numpy = [d for d in project["dependencies"] if re.match(r"numpy\b", d) and ";" not in d]
    assert len(numpy) == 1
    floor = re.fullmatch(r"numpy>=([\d.]+)", numpy[0])
    assert floor is not None, numpy[0]
    assert _python_floor(data) >= NUMPY_PYTHON_FLOOR[_version(floor[1])]


def test_mypy_and_ruff_target_the_python_floor() -> None:
    data = _pyproject()
    major, minor = _python_floor(data)
    tool = data["tool"]
    assert isinstance(tool, dict)
    assert tool["mypy"]["python_version"] == f"{major}.{minor}"
    assert tool["ruff"]["target-version"] == f"py{major}{minor}"
