"""Every name ``navkit`` exports is in the API reference, ``__version__`` too (review 44).

``navkit.__version__`` had no page: the API reference began with
``navkit.geometry``, and the default filter (``!^_``) hides dunder names. The
top-level page ``docs/api/navkit.md`` now renders it, with the docstring that
mkdocstrings shows (a string literal right after the assignment).
"""

from __future__ import annotations

import ast
import inspect
import re
from pathlib import Path

import navkit
import navkit.errors

ROOT = Path(__file__).resolve().parents[1]
API = ROOT / "docs" / "api"


def _directives() -> dict[str, list[str] | None]:
    """Each ``::: target`` of the API pages: the ``members`` it lists (None: all public)."""
    found: dict[str, list[str] | None] = {}
    for page in sorted(API.glob("*.md")):
        text = page.read_text(encoding="utf-8")
        for match in re.finditer(r"^::: ([\w.]+)\s*\n((?:[ ]{4}.*\n)*)", text, re.M):
            members = re.search(r"^\s+members:\s*\[(.*)\]\s*$", match[2], re.M)
            found[match[1]] = (
                None if members is None else re.findall(r"[\"']([\w.]+)[\"']", members[1])
            )
    return found


def test_every_top_level_name_is_rendered_on_an_api_page() -> None:
    directives = _directives()
    assert "navkit" in directives, "no API page renders the top-level package"
    assert "navkit.errors" in directives
    top = directives["navkit"] or []
    for name in navkit.__all__:
        if name in navkit.errors.__all__:
            # Rendered on navkit.errors' page, where it is defined (and linked from the top).
            assert getattr(navkit, name) is getattr(navkit.errors, name)
            assert directives["navkit.errors"] is None  # every public name of it
        else:
            # A dunder name shows only when listed: the default filter hides "_" names.
            assert name in top, f"navkit.{name} is not on docs/api/navkit.md"
    assert "[`navkit.errors`](errors.md)" in (API / "navkit.md").read_text(encoding="utf-8")


def test_version_has_the_docstring_mkdocstrings_renders() -> None:
    tree = ast.parse(inspect.getsource(navkit))
    body = tree.body
    (index,) = [
        i
        for i, node in enumerate(body)
        if isinstance(node, ast.Assign)
        and [t.id for t in node.targets if isinstance(t, ast.Name)] == ["__version__"]
    ]
    following = body[index + 1]
    assert isinstance(following, ast.Expr) and isinstance(following.value, ast.Constant)
    assert "navkit --version" in following.value.value
    assert re.fullmatch(r"\d+\.\d+\.\d+(?:(?:a|b|rc)\d+)?(?:\.post\d+)?(?:\.dev\d+)?",
                        navkit.__version__)  # fmt: skip
