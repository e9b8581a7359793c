"""The README's quick start runs as written."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[1] / "README.md"


def test_quick_start_runs(capsys: pytest.CaptureFixture[str]) -> None:
    text = README.read_text(encoding="utf-8")
    section = text.split("## Quick start", 1)[1]
    block = re.search(r"```python\n(.*?)```", section, re.DOTALL)
    assert block is not None, "README has no python quick start block"
    exec(compile(block.group(1), str(README), "exec"), {})
    assert "after 5 s" in capsys.readouterr().out


def test_every_python_example_runs(capsys: pytest.CaptureFixture[str]) -> None:
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(encoding="utf-8"), re.DOTALL)
    assert len(blocks) >= 2
    for block in blocks:
        exec(compile(block, str(README), "exec"), {})
    out = capsys.readouterr().out
    assert "world path of" in out
    metres = float(out.split("points, ")[1].split(" m")[0])
    assert 5.0 < metres < 9.0  # around the wall's top: longer than the 4 m straight line


def test_development_command_is_what_ci_runs() -> None:
    text = README.read_text(encoding="utf-8")
    section = text.split("## Development", 1)[1]
    commands = re.search(r"```bash\n(.*?)```", section, re.DOTALL)
    assert commands is not None
    test_command = commands.group(1).strip().splitlines()[-1]
    ci = (README.parent / ".ci" / "run").read_text(encoding="utf-8")
    assert test_command in ci.splitlines()


def test_first_command_installs_and_runs_the_demo() -> None:
    text = README.read_text(encoding="utf-8")
    section = text.split("## Install and run", 1)[1]
    block = re.search(r"```bash\n(.*?)```", section, re.DOTALL)
    assert block is not None
    first = block.group(1).strip().splitlines()[0]
    assert first.startswith("python -m pip install -e ") and first.endswith("&& navkit demo")
    pyproject = (README.parent / "pyproject.toml").read_text(encoding="utf-8")
    assert 'navkit = "navkit.cli:main"' in pyproject  # the console script the demo runs through
