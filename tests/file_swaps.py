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
    """Call ``swap()`` once ``Path.stat``, ``exists``, ``is_file`` or ``is_dir`` has been
    called ``after`` times on ``target``: a file changed after its checks.

    Python 3.14's ``exists``, ``is_file`` and ``is_dir`` no longer call ``Path.stat``
    (up to 3.13 they did, and count once: the ``stat`` inside them is not counted)."""
    calls = [0]
    depth = [0]

    def counted(real: Callable[..., Any]) -> Callable[..., Any]:
        def method(self: Path, *args: Any, **kwargs: Any) -> Any:
            depth[0] += 1
            try:
                result = real(self, *args, **kwargs)
            finally:
                depth[0] -= 1
            if depth[0] == 0 and self == target:
                calls[0] += 1
                if calls[0] == after:
                    swap()
            return result

        return method

    for name in ("stat", "exists", "is_file", "is_dir"):
        monkeypatch.setattr(Path, name, counted(getattr(Path, name)))


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
