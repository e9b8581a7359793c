"""docs/deprecations.md: every renamed keyword it lists exists under both names, and warns."""

from __future__ import annotations

import importlib
import inspect
import re
from pathlib import Path
from typing import Any

import pytest

PAGE = Path(__file__).resolve().parents[1] / "docs" / "deprecations.md"
ROW = re.compile(r"^\| `(navkit\.[\w.]+)`[^|]*\| `(\w+)`[^|]*\| `(\w+)`[^|]*\|", re.M)
ROWS = ROW.findall(PAGE.read_text(encoding="utf-8"))


def _resolve(path: str) -> Any:
    parts = path.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj: Any = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for part in parts[i:]:
            obj = getattr(obj, part)
        return obj
    raise AssertionError(path)


def test_the_page_lists_renames() -> None:
    assert len(ROWS) >= 20


@pytest.mark.parametrize(("where", "old", "new"), ROWS, ids=[f"{w}-{o}" for w, o, _ in ROWS])
def test_old_and_new_names_are_both_accepted(where: str, old: str, new: str) -> None:
    parameters = inspect.signature(_resolve(where)).parameters
    assert new in parameters
    assert parameters[old].kind is inspect.Parameter.KEYWORD_ONLY
    assert parameters[old].default is None  # "not passed": renamed_keyword then takes the new one
    doc = inspect.getdoc(_resolve(where)) or ""
    # Documented under its old name too (numpydoc "name : type" lines, possibly grouped).
    assert re.search(rf"^\s*(\w+, )*{old}(, \w+)* :", doc, re.M), old
