"""``navkit --version`` whose line cannot be written exits 0 without a traceback (review 19).

Session 22 replaced argparse's version action with ``_Version`` (one line on
narrow terminals, nothing when standard output is closed). argparse's action
writes through ``ArgumentParser._print_message``, which drops a line that
cannot be written; ``_Version`` wrote it itself, so ``navkit --version | true``
(the reader gone: BrokenPipeError) and ``navkit --version > /dev/full``
(ENOSPC) ended in a traceback and exit code 1, where they used to exit 0.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

_MAIN = "import sys; from navkit.cli import main; sys.exit(main())"


def _run_into(stdout: int) -> subprocess.CompletedProcess[str]:
    # os.environ: NUMBA_CACHE_DIR stays in the child's environment.
    return subprocess.run(
        [sys.executable, "-c", _MAIN, "--version"],
        stdout=stdout, stderr=subprocess.PIPE, text=True, timeout=120,
        env=dict(os.environ), check=False,
    )  # fmt: skip


def test_version_into_a_pipe_whose_reader_is_gone() -> None:
    read_end, write_end = os.pipe()
    os.close(read_end)  # closed before the child writes: its write fails (EPIPE)
    try:
        done = _run_into(write_end)
    finally:
        os.close(write_end)
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr
    assert "Error" not in done.stderr


@pytest.mark.skipif(not Path("/dev/full").exists(), reason="no /dev/full here")
def test_version_into_a_full_device() -> None:
    with open("/dev/full", "w") as full:
        done = _run_into(full.fileno())
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr


def test_version_still_prints_its_line() -> None:
    done = _run_into(subprocess.PIPE)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("navkit ")
    assert done.stdout.count("\n") == 1
