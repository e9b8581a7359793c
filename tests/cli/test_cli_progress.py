"""Progress on terminals only, and the notice that kernels are being compiled (issue 14)."""

from __future__ import annotations

import io
from pathlib import Path

import pytest
from numba.core import config

from navkit.cli import _kernels, _progress
from navkit.cli._kernels import announce_compilation, cache_folders, kernels_cached
from navkit.cli._progress import ProgressBar
from navkit.sim.scenarios import Demo


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_a_bar_on_a_terminal(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(_progress, "DELAY", 0.0)
    stream = Terminal()
    with ProgressBar(stream, enabled=True, description="demo") as bar:
        bar.start(4)
        for k in range(1, 5):
            bar(k, 4)
        assert bar.shown
    text = stream.getvalue()
    assert "demo" in text and "4/4" in text and "trial" in text


@pytest.mark.parametrize(("stream", "enabled"), [(io.StringIO(), True), (Terminal(), False)])
def test_no_bar_in_pipes_or_when_quiet(
    monkeypatch: pytest.MonkeyPatch, stream: io.StringIO, enabled: bool
) -> None:
    monkeypatch.setattr(_progress, "DELAY", 0.0)
    with ProgressBar(stream, enabled=enabled, description="demo") as bar:
        bar.start(2)
        bar(1, 2)
        bar(2, 2)
        assert not bar.shown
    assert stream.getvalue() == ""


def test_a_cold_cache_is_announced(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    demo = Demo(map="office", duration=0.1)
    demo.run_trial(demo.trials(1)[0])  # the simulation's kernels are compiled and cached
    assert kernels_cached("simulation")
    notice = io.StringIO()
    assert not announce_compilation("simulation", notice)
    assert notice.getvalue() == ""
    # An empty NUMBA_CACHE_DIR: nothing cached there.
    monkeypatch.setattr(config, "CACHE_DIR", str(tmp_path))
    assert cache_folders("navkit.sim")[0].parent == tmp_path
    assert not kernels_cached("simulation")
    assert announce_compilation("simulation", notice)
    assert "compiling navkit's kernels once (about 10 s), cached afterwards" in notice.getvalue()


def test_every_key_kernel_exists() -> None:
    # The cache check looks for these functions' index files: they must stay real kernels.
    import importlib

    for (package, module, function), seconds in _kernels.KERNELS.values():
        kernel = getattr(importlib.import_module(f"{package}.{module}"), function)
        assert hasattr(kernel, "py_func") and seconds > 0.0
