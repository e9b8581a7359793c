"""The command's entry point: gaps a mutation review of ``navkit.cli._app`` found.

Review 45, MUTANT23. Each test here failed on a mutant of ``main``, ``_NamedOutput`` or ``_main``
that every earlier test passed.
"""

from __future__ import annotations

import errno
import io
import os
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import cast

import pytest

from navkit.cli import main


def test_empty_bytes_as_argv_is_refused() -> None:
    # bytes are a Sequence whose items (ints) are no str, so only the empty bytes
    # reach the item check vacuously: the type itself must refuse them, not run
    # the command with no arguments.
    with pytest.raises(TypeError, match=r"^argv must be a sequence of str or None, got b''"):
        main(cast(Sequence[str], b""))


def test_closed_standard_error_still_ends_with_the_exit_code(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    # `navkit plan ... 2>&-`: Python's sys.stderr is None. The error line goes to
    # /dev/null and the command still exits 1, not with an AttributeError on None.
    monkeypatch.setattr(sys, "stderr", None)
    missing = str(tmp_path / "missing.yaml")
    assert main(["plan", missing, "--start", "0,0", "--goal", "1,1"]) == 1
    assert capsys.readouterr().out == ""


class _NamedFileOutput(io.StringIO):
    """A standard output (a tee into a log file, say) whose own write errors name their file."""

    def write(self, text: str) -> int:
        raise OSError(errno.EIO, os.strerror(errno.EIO), "navkit-log.txt")


def test_a_write_error_naming_its_own_file_keeps_that_name(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    # "standard output" is put only where the system named no file.
    monkeypatch.setattr(sys, "stdout", _NamedFileOutput())
    assert main(["list"]) == 1
    reason = os.strerror(errno.EIO)
    assert capsys.readouterr().err == f"navkit: error: navkit-log.txt: {reason}\n"


class _GoneReader:
    """A standard output whose reader went away, with no usable descriptor of its own."""

    def __init__(self, fileno_error: type[Exception] | None) -> None:
        self.fileno_error = fileno_error

    def write(self, text: str) -> int:
        raise BrokenPipeError(errno.EPIPE, os.strerror(errno.EPIPE))

    def flush(self) -> None:
        pass

    def __getattr__(self, name: str) -> object:
        if name == "fileno" and self.fileno_error is not None:
            error = self.fileno_error

            def fileno() -> int:
                raise error("no descriptor")

            return fileno
        raise AttributeError(name)


@pytest.mark.parametrize(
    "fileno_error",
    [None, ValueError, OSError],
    ids=["no fileno", "closed file (ValueError)", "fileno fails (OSError)"],
)
def test_a_gone_reader_without_a_descriptor_still_ends_quietly_with_141(
    fileno_error: type[Exception] | None,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
) -> None:
    # An embedder's or a test's standard output (no fileno, a closed file's
    # ValueError, a failing OSError) has no descriptor to point at /dev/null:
    # the closed pipe still ends the command as 141, not with that error.
    monkeypatch.setattr(sys, "stdout", _GoneReader(fileno_error))
    assert main(["list"]) == 141
    assert capsys.readouterr().err == ""
