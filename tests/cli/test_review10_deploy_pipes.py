"""The command with standard output closed, or a reader that has gone (``| head -1``)."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX file descriptors")


def _env(**extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_DISABLE")}
    env.update(extra)
    return env


def test_closed_standard_output_runs_the_command_quietly() -> None:
    # `navkit list >&-`: Python's sys.stdout is None, and the final flush raised
    # AttributeError: 'NoneType' object has no attribute 'flush' (a traceback).
    done = subprocess.run(
        ["/bin/sh", "-c", 'exec "$0" -m navkit list >&-', sys.executable],
        env=_env(), capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stderr == ""


def test_closed_standard_error_still_reports_by_exit_code() -> None:
    done = subprocess.run(
        ["/bin/sh", "-c", 'exec "$0" -m navkit plan /nonexistent.yaml --start 0,0 --goal 1,1 '
                          '2>&-', sys.executable],
        env=_env(), capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert done.returncode == 1
    assert done.stdout == ""


@pytest.mark.parametrize("ascii_locale", [False, True])
def test_a_gone_reader_ends_the_command_quietly(ascii_locale: bool) -> None:
    extra = {"LC_ALL": "C", "PYTHONUTF8": "0", "PYTHONCOERCECLOCALE": "0"} if ascii_locale else {}
    read, write = os.pipe()
    os.close(read)  # the reader is gone before navkit writes
    try:
        child = subprocess.Popen(
            [sys.executable, "-m", "navkit", "list"], stdout=write, stderr=subprocess.PIPE,
            env=_env(**extra),
        )  # fmt: skip
    finally:
        os.close(write)
    _, err = child.communicate(timeout=300)
    assert child.returncode == 141
    assert err == b""
