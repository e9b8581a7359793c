"""The sweep's progress bar: its size, clean-up and monitor thread (review 43, MUTANT14).

A mutation review of ``navkit.cli._progress`` left these changes without a
failing test: a terminal reporting one of its sizes (``100 x 0``) given the
fallback's width, or no fixed size; the fallback's 80 x 24; the errors a
stream's descriptor may raise; tqdm's monitor thread left on (sweeps fork
workers while the bar is up); the bar's last line erased at the end, or not
closed; ``start`` drawing nothing; no delay before the bar appears; ``shown``
still True after the block.
"""

from __future__ import annotations

import io
import os
import sys
from pathlib import Path
from typing import Any

import pytest
import tqdm
import tqdm.std

from navkit.cli import _progress
from navkit.cli._progress import ProgressBar, _size


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


class _Fileno(_Terminal):
    def __init__(self, fileno: Any) -> None:
        super().__init__()
        self._fileno = fileno

    def fileno(self) -> int:
        if isinstance(self._fileno, BaseException):
            raise self._fileno
        return int(self._fileno)


@pytest.mark.parametrize(
    ("reported", "expected"),
    [
        ((100, 40), {"dynamic_ncols": True}),
        ((100, 0), {"ncols": 100, "nrows": 24}),
        ((0, 40), {"ncols": 80, "nrows": 40}),
        ((0, 0), {"ncols": 80, "nrows": 24}),
    ],
)
def test_a_size_the_terminal_reports_is_kept_the_other_falls_back(
    monkeypatch: pytest.MonkeyPatch, reported: tuple[int, int], expected: dict[str, Any]
) -> None:
    monkeypatch.setattr(os, "get_terminal_size", lambda fd: os.terminal_size(reported))
    # shutil's fallback, 80 x 24: no $COLUMNS/$LINES, no terminal on standard output.
    monkeypatch.delenv("COLUMNS", raising=False)
    monkeypatch.delenv("LINES", raising=False)
    monkeypatch.setattr(sys, "__stdout__", None)
    assert _size(_Fileno(7)) == expected


def test_a_stream_without_a_usable_descriptor_gets_the_terminals_width(
    tmp_path: Path,
) -> None:
    class NoFileno:
        pass

    with open(tmp_path / "f.txt", "w", encoding="utf-8") as regular:
        not_a_terminal = _Fileno(regular.fileno())  # os.get_terminal_size: OSError
        assert _size(not_a_terminal) == {"dynamic_ncols": True}
    closed = _Fileno(ValueError("I/O operation on closed file"))
    assert _size(closed) == {"dynamic_ncols": True}
    assert _size(NoFileno()) == {"dynamic_ncols": True}  # type: ignore[arg-type]


def test_the_bar_starts_keeps_its_last_line_and_ends(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(_progress, "DELAY", 0.0)
    monkeypatch.setattr(tqdm.tqdm, "monitor_interval", 10)
    monkeypatch.setattr(tqdm.tqdm, "monitor", None)
    stream = _Terminal()
    with ProgressBar(stream, enabled=True, description="demo") as bar:
        bar.start(4)
        started = bar.shown
        assert "0/4" in stream.getvalue()
        bar(1, 4)
        bar(3, 4)
        bar(4, 4)
        assert tqdm.tqdm.monitor is None  # no monitor thread while workers fork
    assert started and not bar.shown  # closed at the block's end
    last = stream.getvalue().split("\r")[-1]
    assert last.startswith("demo") and "4/4" in last and last.endswith("\n")


@pytest.mark.parametrize(("elapsed", "drawn"), [(0.0, False), (1.9, False), (2.1, True)])
def test_the_bar_appears_once_the_run_has_lasted_two_seconds(
    monkeypatch: pytest.MonkeyPatch, elapsed: float, drawn: bool
) -> None:
    # tqdm's own clock, set by hand: no wall-clock time in the test.
    now = [1000.0]
    monkeypatch.setattr(tqdm.std, "time", lambda: now[0])
    stream = _Terminal()
    with ProgressBar(stream, enabled=True, description="demo") as bar:
        bar.start(4)
        now[0] += elapsed
        bar(1, 4)
    assert ("1/4" in stream.getvalue()) is drawn
