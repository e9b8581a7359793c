"""The command's one-line errors and exit codes: gaps a mutation review found (review 44, MUTANT17).

Each test here failed on a mutant of ``navkit.cli._app`` that every earlier
test passed: an error without a message, an OSError without a reason, one
naming two files.
"""

from __future__ import annotations

import errno
import io
import os
import sys
from pathlib import Path

import pytest

from navkit.cli import main
from navkit.cli._app import one_line


@pytest.mark.parametrize("exc", [ValueError(), OSError(), RuntimeError(" \n ")])
def test_an_error_without_a_message_is_named_by_its_type(exc: BaseException) -> None:
    # Not an empty "navkit: error: " line.
    assert one_line(exc) == type(exc).__name__


def test_an_os_error_naming_two_files_names_both(tmp_path: Path) -> None:
    missing, target = tmp_path / "missing.json", tmp_path / "out" / "p.json"
    with pytest.raises(FileNotFoundError) as caught:
        os.rename(missing, target)
    reason = os.strerror(errno.ENOENT)
    assert one_line(caught.value) == f"{missing} -> {target}: {reason}"


@pytest.mark.parametrize(
    "exc",
    [OSError(errno.EIO, None), OSError(errno.EIO, None, "f.txt"), OSError(errno.EIO, "", "f.txt")],
)
def test_an_os_error_without_a_reason_keeps_pythons_text(exc: OSError) -> None:
    # "file: reason" needs a reason: without one, Python's "[Errno 5] ..." is kept
    # (not "f.txt: None", "f.txt: " or an AttributeError on None).
    assert one_line(exc) == " ".join(str(exc).split())


class _FullDisk(io.StringIO):
    """A standard output on a full disk: its writes, or only its flushes, fail."""

    def __init__(self, failing: str) -> None:
        super().__init__()
        self.failing = failing

    def write(self, text: str) -> int:
        if self.failing == "write":
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return super().write(text)

    def flush(self) -> None:
        if self.failing == "flush":
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


@pytest.mark.parametrize("failing", ["write", "flush"])
def test_a_failed_write_to_standard_output_names_it(
    failing: str, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    # The system's error names no file: "No space left on device" alone left the
    # user guessing among the command's files. Write and flush fail apart (a
    # buffered stream fails in either).
    monkeypatch.setattr(sys, "stdout", _FullDisk(failing))
    assert main(["list"]) == 1
    reason = os.strerror(errno.ENOSPC)
    assert capsys.readouterr().err == f"navkit: error: standard output: {reason}\n"


def test_notes_are_joined_on_the_line_each_on_one_line() -> None:
    exc = ValueError("bad map")
    exc.add_note("see\n   the docs")
    exc.add_note("  twice ")
    assert one_line(exc) == "bad map; see the docs; twice"
