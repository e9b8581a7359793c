"""The documentation's examples run as written.

Every ```python block of every page under ``docs/`` runs, page by page (the
blocks of one page share a namespace, as a reader would run them), from the
repository root so that paths to ``../shared/data`` resolve; pages that use the
real data sets skip when they are absent.
"""

from __future__ import annotations

import gc
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
    try:
        for block in re.findall(r"```python\n(.*?)```", text, re.DOTALL):
            exec(compile(block, str(page), "exec"), namespace)
    finally:
        gc.unfreeze()  # a page's gc.freeze() (compilation.md) is for a robot's process


def test_docs_have_examples() -> None:
    assert PAGES, "no page under docs/ has a python example"
    assert os.path.isfile(DOCS.parent / "mkdocs.yml")


# ```bash blocks that feed a script to ``python - <<'TAG'``: test_page_examples_run
# only sees ```python blocks, so these escaped it.
HEREDOCS = [
    pytest.param(script, id=f"{page.relative_to(DOCS)}:{n}")
    for page in sorted(DOCS.rglob("*.md"))
    for n, script in enumerate(
        m.group(2)
        for block in re.findall(r"```bash\n(.*?)```", page.read_text(encoding="utf-8"), re.DOTALL)
        for m in re.finditer(r"python - <<'(\w+)'\n(.*?)\n\1\n", block, re.DOTALL)
    )
]


@pytest.mark.parametrize("script", HEREDOCS)
def test_python_heredocs_in_shell_examples_run(
    script: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(ROOT)
    exec(compile(script, "<heredoc>", "exec"), {"__name__": "__main__"})


def test_heredocs_are_found() -> None:
    assert HEREDOCS, "docs/compilation.md warms the cache with a python heredoc"


def _ratios(text: str, peer: str, workloads: str) -> list[float]:
    """The ``ratio peer/navkit`` column of performance.md's rows of ``peer``."""
    out = []
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 8 and cells[3] == peer and re.fullmatch(workloads, cells[0]):
            out.append(float(cells[6]))
    return out


def test_performance_ranges_match_the_table() -> None:
    """The caveats quote ranges of the results table; they must be the table's."""
    text = (DOCS / "performance.md").read_text(encoding="utf-8")
    python = _ratios(text, "pure-Python heapq A*", r"astar-.*")
    assert python, "no pure-Python A* rows"
    quoted = re.search(r"`astar-\*`\s+rows \((\d+)–(\d+)×\)", text)
    assert quoted is not None
    assert (int(quoted[1]), int(quoted[2])) == (round(min(python)), round(max(python)))
    pyastar = _ratios(text, "pyastar2d", r".*")
    quoted = re.search(r"ratios ([\d.]+)–([\d.]+) in this run", text)
    assert quoted is not None
    assert (float(quoted[1]), float(quoted[2])) == (round(min(pyastar), 2), round(max(pyastar), 2))


def test_getting_started_quotes_the_readmes_first_two_commands() -> None:
    """The page says it shows "the README's first command" and "the second"."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8").split("## Install and run", 1)[1]
    page = (DOCS / "getting-started.md").read_text(encoding="utf-8")
    bash = r"```bash\n(.*?)```"
    assert re.findall(bash, page, re.DOTALL)[:2] == re.findall(bash, readme, re.DOTALL)[:2]
