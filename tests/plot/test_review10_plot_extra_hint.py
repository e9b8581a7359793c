"""The install hint of navkit.plot without matplotlib survives the user's shell.

``pip install navkit[plot]`` unquoted is a glob: zsh stops with "no matches
found" and bash replaces it by a matching file (``navkitp``) in the current
folder, so the hint installed the wrong thing or nothing.
"""

from __future__ import annotations

import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.plot import plot_grid


def _hint(monkeypatch: pytest.MonkeyPatch) -> str:
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    with pytest.raises(ImportError) as info:
        plot_grid(OccupancyGrid.from_occupancy(np.eye(3, dtype=bool), resolution=0.5))
    found = re.search(r"pip install \S+", str(info.value))
    assert found is not None, str(info.value)
    return found.group(0)


def test_the_hint_names_the_extra_as_one_quoted_word(monkeypatch: pytest.MonkeyPatch) -> None:
    hint = _hint(monkeypatch)
    assert shlex.split(hint) == ["pip", "install", "navkit[plot]"]
    # Quoted, so that no shell takes the brackets for a glob.
    assert re.search(r"(['\"])navkit\[plot\]\1", hint), hint


@pytest.mark.parametrize("shell", ["bash", "zsh"])
def test_the_hint_pasted_into_a_shell_asks_pip_for_the_extra(
    shell: str, monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    program = shutil.which(shell)
    if program is None:
        pytest.skip(f"{shell} is not installed")
    command = _hint(monkeypatch)
    (tmp_path / "navkitp").touch()  # what the unquoted brackets match
    # printf stands in for pip: it prints the arguments the shell passes on.
    done = subprocess.run([program, "-c", command.replace("pip", "printf '%s\\n'", 1)],
                          cwd=tmp_path, capture_output=True, text=True, check=False)  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["install", "navkit[plot]"]
