"""Swapping a file for a FIFO or a folder after a reader's checks of it.

Shared by the map-file and bag-file swap tests (``tests/mapping``).
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest


def swap_after_stats(monkeypatch: pytest.MonkeyPatch, target: Path, after: int,
                     swap: Callable[[], None]) -> None:  # fmt: skip
    """Call ``swap()`` once ``Path.stat`` (behind ``exists``, ``is_file``, ``is_dir``)
    has been called ``after`` times on ``target``: a file changed after its checks."""
    real_stat = Path.stat
    calls = [0]

    def stat(self: Path, *args: Any, **kwargs: Any) -> Any:
        result = real_stat(self, *args, **kwargs)
        if self == target:
            calls[0] += 1
            if calls[0] == after:
                swap()
        return result

    monkeypatch.setattr(Path, "stat", stat)


def to_fifo(path: Path) -> Callable[[], None]:
    """A swap that replaces the file ``path`` by a FIFO."""

    def swap() -> None:
        path.unlink()
        os.mkfifo(path)

    return swap


def to_folder(path: Path) -> Callable[[], None]:
    """A swap that replaces the file ``path`` by an empty folder."""

    def swap() -> None:
        path.unlink()
        path.mkdir()

    return swap
