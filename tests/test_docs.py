"""The documentation's examples run as written.

Every ```python block of every page under ``docs/`` runs, page by page (the
blocks of one page share a namespace, as a reader would run them), from the
repository root so that paths to ``../shared/data`` resolve; pages that use the
real data sets skip when they are absent.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
PAGES = sorted(p for p in DOCS.rglob("*.md") if "```python" in p.read_text(encoding="utf-8"))
SHARED = ROOT.parent / "shared" / "data"


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(DOCS)))
def test_page_examples_run(page: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    text = page.read_text(encoding="utf-8")
    if "shared/data" in text and not SHARED.is_dir():
        pytest.skip(f"{page.name} uses {SHARED}, which is absent")
    monkeypatch.chdir(ROOT)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    namespace: dict[str, object] = {"__name__": f"docs_{page.stem}"}
    for block in re.findall(r"```python\n(.*?)```", text, re.DOTALL):
        exec(compile(block, str(page), "exec"), namespace)


def test_docs_have_examples() -> None:
    assert PAGES, "no page under docs/ has a python example"
    assert os.path.isfile(DOCS.parent / "mkdocs.yml")
