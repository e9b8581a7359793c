"""Ctrl-C at any moment of a ``navkit`` command: exit code 130, one line, no traceback."""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import sys
from collections.abc import Sequence
from types import ModuleType

import pytest

import navkit.cli


class _InterruptedImport(importlib.abc.MetaPathFinder):
    """A Ctrl-C arriving while ``navkit.cli._app`` (numba, scipy, the simulator) loads."""

    def find_spec(
        self, fullname: str, path: Sequence[str] | None, target: ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        if fullname == "navkit.cli._app":
            raise KeyboardInterrupt
        return None


def test_ctrl_c_while_the_command_loads_exits_130_in_one_line(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.delitem(sys.modules, "navkit.cli._app", raising=False)
    monkeypatch.setattr(sys, "meta_path", [_InterruptedImport(), *sys.meta_path])
    assert navkit.cli.main(["list"]) == 130
    captured = capsys.readouterr()
    assert captured.err == "navkit: interrupted\n"
    assert captured.out == ""


def test_importing_the_command_does_not_load_its_modules() -> None:
    # What keeps the window for an uncaught Ctrl-C (a traceback) to the interpreter's start.
    import subprocess

    code = "import sys, navkit.cli; print('navkit.cli._app' in sys.modules, 'numpy' in sys.modules)"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["False", "False"]


def test_main_still_runs_the_command(capsys: pytest.CaptureFixture[str]) -> None:
    assert navkit.cli.main(["--version"]) == 0
    assert capsys.readouterr().out.startswith("navkit ")
