"""A closed pipe on standard output leaks no descriptor (review 30, FNF).

On ``BrokenPipeError`` the command points its standard output at ``/dev/null``
(so that the interpreter's last flush does not fail again) and exits 141. It did
so with ``os.dup2(os.open(os.devnull, ...), sys.stdout.fileno())``: the descriptor
``os.open`` returned was never closed, one more open per call of ``main`` (tests
and embedders call it many times in one process), and one opened even when
standard output had no descriptor (``fileno`` raising).
"""

from __future__ import annotations

import errno
import gc
import io
import os
import sys
from pathlib import Path

import pytest

from navkit.cli import main

pytestmark = pytest.mark.skipif(
    not os.path.isdir("/proc/self/fd"), reason="counts descriptors in /proc/self/fd"
)


def _open_fds() -> int:
    gc.collect()
    return len(os.listdir("/proc/self/fd"))


class _ClosedPipe(io.StringIO):
    """Standard output whose reader went away, on the descriptor ``fd`` (None: none)."""

    def __init__(self, fd: int | None) -> None:
        super().__init__()
        self._fd = fd

    def write(self, text: str) -> int:
        raise BrokenPipeError(errno.EPIPE, os.strerror(errno.EPIPE))

    def fileno(self) -> int:
        if self._fd is None:
            raise io.UnsupportedOperation("no file")
        return self._fd


def test_the_devnull_swap_keeps_no_descriptor_of_its_own(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    with open(tmp_path / "out.txt", "wb") as standing_in:
        fd = standing_in.fileno()
        monkeypatch.setattr(sys, "stdout", _ClosedPipe(fd))
        before = _open_fds()
        for _ in range(3):
            assert main(["list"]) == 141
        assert _open_fds() == before
        # The swap itself still happened: the descriptor now writes to /dev/null.
        assert os.path.samestat(os.fstat(fd), os.stat(os.devnull))
    assert capsys.readouterr().err == ""


def test_standard_output_without_a_descriptor_opens_nothing(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr(sys, "stdout", _ClosedPipe(None))
    before = _open_fds()
    assert main(["list"]) == 141
    assert _open_fds() == before
    assert capsys.readouterr().err == ""
