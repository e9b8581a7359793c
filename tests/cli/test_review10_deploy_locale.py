"""The command under a locale without "×" or "±" (LC_ALL=C without Python's UTF-8 mode)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.cli._encoding import ERRORS
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import write_map

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX locales")


def _ascii_env() -> dict[str, str]:
    dropped = ("LC_", "LANG", "PYTHONIOENCODING", "PYTHONUTF8", "NUMBA_")
    # NUMBA_CACHE_DIR kept: without it the plan's kernels were cached in the
    # checkout's src/ (numba's default, beside the sources).
    env = {
        k: v for k, v in os.environ.items()
        if not k.startswith(dropped) or k == "NUMBA_CACHE_DIR"
    }  # fmt: skip
    env.update(LC_ALL="C", PYTHONUTF8="0", PYTHONCOERCECLOCALE="0")
    return env


def _navkit(*args: str | bytes) -> subprocess.CompletedProcess[bytes]:
    return subprocess.run(
        [sys.executable, "-m", "navkit", *args], env=_ascii_env(), capture_output=True,
        timeout=300,
    )  # fmt: skip


def test_list_prints_ascii_stand_ins() -> None:
    # The titles' "14.4 × 12 m" raised UnicodeEncodeError: "navkit: error: 'ascii'
    # codec can't encode character '\xd7'", exit code 1, and no list.
    done = _navkit("list")
    assert done.returncode == 0, done.stderr.decode(errors="replace")
    assert b"14.4 x 12 m" in done.stdout
    assert done.stdout.isascii() and done.stderr == b""


def test_a_map_in_a_non_ascii_folder(tmp_path: Path) -> None:
    folder = tmp_path / "karte_ü"
    folder.mkdir()
    occupied = np.zeros((10, 12), dtype=bool)
    occupied[:6, 6] = True
    write_map(OccupancyGrid.from_occupancy(occupied, resolution=0.1), folder / "m.yaml")
    picture = folder / "p.png"
    done = _navkit(
        "plan", os.fsencode(folder / "m.yaml"), "--start", "0.15,0.15", "--goal", "1.05,0.15",
        "--plot", os.fsencode(picture), "--quiet",
    )  # fmt: skip
    assert done.returncode == 0, done.stderr.decode(errors="replace")
    assert picture.is_file()
    assert b"wrote " + os.fsencode(picture) in done.stdout  # the name's bytes as given


def test_stand_ins() -> None:
    text = "± 2 m, 45°, σ ≈ 0.1, a → b, Gauss–Newton, ü, \u2603"
    expected = b"+/- 2 m, 45 deg, sigma ~ 0.1, a -> b, Gauss-Newton, u, ?"
    assert text.encode("ascii", ERRORS) == expected
    assert "karte_\udcc3\udcbc".encode("ascii", ERRORS) == "karte_ü".encode()
    assert "×".encode("latin-1", ERRORS) == "×".encode("latin-1")  # only what is missing
